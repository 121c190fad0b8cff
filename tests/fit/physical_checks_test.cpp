// The sentences a fit adds when its values describe no real knob.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "knoblab/fit/physical_checks.hpp"
#include "knoblab/fit/result_json.hpp"
#include "knoblab/fit/validation_data.hpp"

namespace knoblab::fit {
namespace {

// A thesis6 result with every value and interval given by hand (SI).
FitResult result(double M, std::array<double, 2> M_ci, double C_pos, std::array<double, 2> C_pos_ci,
                 double B_pos) {
  FitResult r;
  r.model = ModelKind::Thesis6;
  r.names = param_names(r.model);
  r.params = {M, 1e-3, 5e-4, C_pos, B_pos, 0, 1, 0};
  r.fitted = {true, true, true, true, true, false, false, false};
  r.se.assign(8, 0.0);
  r.ci95 = {M_ci, {0.9e-3, 1.1e-3}, {4e-4, 6e-4}, C_pos_ci, {0.9 * B_pos, 1.1 * B_pos}, {0, 0}, {1, 1}, {0, 0}};
  return r;
}

TEST(PhysicalChecks, AFitOfAPhysicalKnobHasNoWarnings) {
  const FitResult r = fit_knob(make_validation_data(ValidationSpec{}));
  EXPECT_TRUE(physical_warnings(r).empty());
  EXPECT_EQ(nlohmann::json::parse(to_json(r))["warnings"], nlohmann::json::array());
}

TEST(PhysicalChecks, ANegativeCoulombTermSaysBelowWhichSpeedTheKnobIsPushedAlong) {
  const FitResult r = result(5e-5, {4e-5, 6e-5}, -2e-3, {-3e-3, -1e-3}, 0.5e-3);
  const auto w = physical_warnings(r);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("C_vel_pos is negative (-2 mN·m, 95 % interval [-3, -1])"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("turning forwards"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("below 4 rad/s"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("energy-producing"), std::string::npos) << w[0];
  EXPECT_EQ(nlohmann::json::parse(to_json(r))["warnings"].size(), 1u);
}

TEST(PhysicalChecks, ANegativeValueWhoseIntervalReachesZeroIsUnresolvedNotUnphysical) {
  EXPECT_TRUE(physical_warnings(result(5e-5, {4e-5, 6e-5}, -0.2e-3, {-1e-3, 0.6e-3}, 0.5e-3)).empty());
}

TEST(PhysicalChecks, AnInertiaIntervalSpanningZeroSaysTheInertiaIsNotIdentified) {
  const auto w = physical_warnings(result(1e-6, {-2e-6, 4e-6}, 1e-3, {0.9e-3, 1.1e-3}, 0.5e-3));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("M_acc is not identified"), std::string::npos) << w[0];
}

TEST(PhysicalChecks, NegativeInertiaIsFlagged) {
  const auto w = physical_warnings(result(-3e-5, {-4e-5, -2e-5}, 1e-3, {0.9e-3, 1.1e-3}, 0.5e-3));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("M_acc is negative"), std::string::npos) << w[0];
}

}  // namespace
}  // namespace knoblab::fit
