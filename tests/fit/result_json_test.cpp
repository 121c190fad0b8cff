// The fit's JSON: the names outside tools read (docs/fit.md).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "knoblab/fit/result_json.hpp"
#include "knoblab/fit/validation_data.hpp"

namespace knoblab::fit {
namespace {

TEST(ResultJson, HasTheDocumentedNamesInSiUnits) {
  const FitResult r = fit_knob(make_validation_data(ValidationSpec{}));
  const auto j = nlohmann::json::parse(to_json(r));
  EXPECT_EQ(j["model"], "thesis6");
  const std::vector<std::string> names = {"M_acc", "C_vel_neg", "B_vel_neg", "C_vel_pos",
                                          "B_vel_pos", "A_pos", "P_pos", "S_pos"};
  ASSERT_EQ(j["params"].size(), names.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    ASSERT_TRUE(j["params"].contains(names[k])) << names[k];
    EXPECT_DOUBLE_EQ(j["params"][names[k]].get<double>(), r.params[k]);
    ASSERT_TRUE(j["ci95"][names[k]].is_array());
    EXPECT_DOUBLE_EQ(j["ci95"][names[k]][0].get<double>(), r.ci95[k][0]);
    EXPECT_DOUBLE_EQ(j["ci95"][names[k]][1].get<double>(), r.ci95[k][1]);
  }
  // Eq. 10's sign convention: magnitudes near the targets, not negated.
  EXPECT_NEAR(j["params"]["C_vel_neg"].get<double>(), 1.5, 0.1);
  EXPECT_NEAR(j["params"]["B_vel_neg"].get<double>(), 1.0, 0.05);
  for (const char* key : {"rmse_Nm", "fit_percent", "bic", "iterations", "seconds"}) {
    EXPECT_TRUE(j[key].is_number()) << key;
  }
  EXPECT_NEAR(j["detents"]["per_rev"].get<double>(), 5.0, 0.05);
}

TEST(ResultJson, HeldParametersHaveNoInterval) {
  FitResult r;
  r.model = ModelKind::Thesis6;
  r.names = param_names(r.model);
  r.params = {1, 2, 3, 4, 5, 0, 1, 0};
  r.fitted = {true, true, true, true, true, false, false, false};
  r.se.assign(8, 0.1);
  r.ci95.assign(8, {0, 1});
  const auto j = nlohmann::json::parse(to_json(r));
  EXPECT_TRUE(j["ci95"]["A_pos"].is_null());
  EXPECT_TRUE(j["ci95"]["M_acc"].is_array());
  EXPECT_EQ(j["held"], nlohmann::json({"A_pos", "P_pos", "S_pos"}));
  EXPECT_FALSE(j["detents"]["present"].get<bool>());
  EXPECT_TRUE(j["stick"].is_null());
  const auto k = nlohmann::json::parse(knob_json(r));
  EXPECT_EQ(k["params"]["B_vel_pos"], 5);
  EXPECT_FALSE(k.contains("stick"));
}

}  // namespace
}  // namespace knoblab::fit
