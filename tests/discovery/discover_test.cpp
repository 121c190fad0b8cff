// discover() on the thesis' validation data (Eq. 8–11, §2.1.2, swept over
// ±4 rad instead of ±1 so that once-per-revolution and unrelated periods are
// resolvable) with one effect from the library added to the torque at about
// the noise's size (concealed: under the noise at most samples), and on the
// clean data.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "findings.hpp"
#include "effect_data.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/model/effects.hpp"

namespace knoblab::discovery {
namespace {

using knoblab::test::param;

using test_data::with_effect;

// The search itself, at noise level: an effect the size of the noise cuts
// the held-out RMS by 10–15 %, under the 20 % bar a reported finding must
// clear (discrepancy.hpp), so these tests lower the bar; the bar has its own
// test (AConsistentGainUnderTheBarIsTentative).
DiscrepancyOptions no_bar() {
  DiscrepancyOptions o;
  o.min_reported_gain = 0.0;
  return o;
}

TEST(Discover, CleanDataHasNoFinding) {
  for (const std::uint64_t seed : {1u, 2u}) {
    const DiscrepancyResult r = discover(with_effect(seed, nullptr));
    EXPECT_TRUE(r.findings.empty()) << "seed " << seed << ": " << to_json(r);
    EXPECT_NEAR(r.final_model.heldout_rmse_Nm, r.base.heldout_rmse_Nm, 1e-12);
    // A sweep that passes its angles again and again keeps the 32 blocks.
    EXPECT_EQ(r.blocks, 32u);
  }
}

TEST(Discover, NamesAnUnbalancedMassAndFitsItsAmplitude) {
  const model::OncePerRev<double> g{1.2, 0.4};
  const DiscrepancyResult r = discover(with_effect(3, [&](const fit::FitData& d, std::size_t i) {
    return g.torque(d.theta[i]);
  }));
  ASSERT_FALSE(r.findings.empty()) << to_json(r);
  const Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, EffectId::Gravity) << to_json(r);
  EXPECT_NEAR(param(f, "amplitude_Nm"), 1.2, 0.25);
  EXPECT_LT(f.heldout_rmse_after_Nm, f.heldout_rmse_before_Nm);
  EXPECT_GT(f.confidence, 0.0);
  EXPECT_FALSE(f.explanation.empty());
}

TEST(Discover, NamesASecondPeriodicTorqueAndItsPeriod) {
  // 11.3 cycles/rev beside the validation model's 5 detents/rev (P = 0.2).
  const model::Detents<double> cogging{0.8, 1.0 / 11.3, 0.5};
  const DiscrepancyResult r = discover(with_effect(4, [&](const fit::FitData& d, std::size_t i) {
    return cogging.torque(d.theta[i]);
  }), no_bar());
  ASSERT_FALSE(r.findings.empty()) << to_json(r);
  const Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, EffectId::PeriodicTorque) << to_json(r);
  EXPECT_NEAR(param(f, "cycles_per_rev"), 11.3, 0.1);
  EXPECT_NEAR(param(f, "period_rad"), 2 * std::numbers::pi / 11.3, 0.01);
}

TEST(Discover, FindsTwoUnrelatedPeriodicTorquesOneAfterTheOther) {
  // Cogging has several components: 11.3 and 17.9 cycles/rev, each weaker
  // than the knob's detents (1.0 at 5/rev), so which one is "the detents" is
  // not in question.
  const model::Detents<double> a{0.6, 1.0 / 11.3, 0.5}, b{0.5, 1.0 / 17.9, -1.0};
  const DiscrepancyResult r = discover(with_effect(6, [&](const fit::FitData& d, std::size_t i) {
    return a.torque(d.theta[i]) + b.torque(d.theta[i]);
  }), no_bar());
  ASSERT_GE(r.findings.size(), 2u) << to_json(r);
  std::vector<double> found;
  for (const Finding& f : r.findings) {
    if (f.effect == EffectId::PeriodicTorque) found.push_back(param(f, "cycles_per_rev"));
  }
  ASSERT_EQ(found.size(), 2u) << to_json(r);
  std::sort(found.begin(), found.end());
  EXPECT_NEAR(found[0], 11.3, 0.1);
  EXPECT_NEAR(found[1], 17.9, 0.1);
  const auto j = nlohmann::json::parse(to_json(r));
  EXPECT_TRUE(j["final"]["params"].contains("periodic_torque#2.cycles_per_rev"));
}

TEST(Discover, NamesNonSinusoidalDetents) {
  // 2nd and 3rd harmonics of the validation model's detents.
  const DiscrepancyResult r = discover(with_effect(5, [&](const fit::FitData& d, std::size_t i) {
    const double phi = d.theta[i] / 0.2 + 0.9;
    return 0.6 * std::sin(2 * phi) + 0.4 * std::cos(3 * phi);
  }), no_bar());
  ASSERT_FALSE(r.findings.empty()) << to_json(r);
  EXPECT_EQ(r.findings.front().effect, EffectId::DetentShape) << to_json(r);
  EXPECT_NEAR(param(r.findings.front(), "h2_amplitude_Nm"), 0.6, 0.15);
}

// Two dips of unequal depth per detent: the second harmonic (2 N·m) outweighs
// the fundamental (1 N·m), so Eq. 6's search takes the harmonic for the
// detents; the shape is found at the detents' own period, not as a torque
// at half the "detents'" frequency.
TEST(Discover, DetentsWhoseSecondHarmonicOutweighsTheFundamentalAreShapedAtTheirOwnPeriod) {
  const DiscrepancyResult r = discover(with_effect(5, [&](const fit::FitData& d, std::size_t i) {
    const double phi = d.theta[i] / 0.2 + 0.9;
    return 2.0 * std::sin(2 * phi) + 0.5 * std::cos(3 * phi);
  }), no_bar());
  ASSERT_FALSE(r.findings.empty()) << to_json(r);
  EXPECT_EQ(r.findings.front().effect, EffectId::DetentShape) << to_json(r);
  EXPECT_NEAR(param(r.findings.front(), "cycles_per_rev"), 5.0, 0.05) << to_json(r);
  EXPECT_NEAR(param(r.findings.front(), "h2_amplitude_Nm"), 2.0, 0.3) << to_json(r);
}

TEST(Discover, AConsistentGainUnderTheBarIsTentative) {
  // The cogging of NamesASecondPeriodicTorqueAndItsPeriod: found and
  // consistent, but it cuts the held-out RMS by less than 20 %.
  const model::Detents<double> cogging{0.8, 1.0 / 11.3, 0.5};
  const fit::FitData d = with_effect(4, [&](const fit::FitData& x, std::size_t i) {
    return cogging.torque(x.theta[i]);
  });
  const DiscrepancyResult r = discover(d);
  EXPECT_TRUE(r.findings.empty()) << to_json(r);
  ASSERT_EQ(r.tentative.size(), 1u) << to_json(r);
  EXPECT_EQ(r.tentative.front().effect, EffectId::PeriodicTorque);
  const double gain = 1.0 - r.tentative_heldout_rmse_Nm / r.base.heldout_rmse_Nm;
  EXPECT_GT(gain, 0.02);
  EXPECT_LT(gain, 0.20);
  // Not adopted: the final model is the base, and says so in the JSON.
  EXPECT_EQ(r.final_model.heldout_rmse_Nm, r.base.heldout_rmse_Nm);
  EXPECT_EQ(r.final_model.params.size(), r.base.params.size());
  const auto j = nlohmann::json::parse(to_json(r));
  EXPECT_TRUE(j["findings"].empty());
  ASSERT_EQ(j["tentative_findings"].size(), 1u);
  EXPECT_EQ(j["tentative_findings"][0]["effect"], "periodic_torque");
  EXPECT_NEAR(j["tentative_heldout_rmse_Nm"].get<double>(), r.tentative_heldout_rmse_Nm, 1e-15);
  for (const auto& c : j["candidates"]) EXPECT_FALSE(c["kept"].get<bool>());
  // A bar under its gain reports it, with the same held-out figure.
  DiscrepancyOptions low;
  low.min_reported_gain = gain - 0.01;
  const DiscrepancyResult reported = discover(d, low);
  ASSERT_EQ(reported.findings.size(), 1u) << to_json(reported);
  EXPECT_TRUE(reported.tentative.empty());
  EXPECT_NEAR(reported.final_model.heldout_rmse_Nm, r.tentative_heldout_rmse_Nm, 1e-6);
}

TEST(Discover, JsonHasTheNamesOutsideToolsRead) {
  const DiscrepancyResult r = discover(with_effect(3, [](const fit::FitData& d, std::size_t i) {
    return 1.2 * std::sin(d.theta[i] + 0.4);
  }));
  const auto j = nlohmann::json::parse(to_json(r));
  for (const char* k : {"base", "findings", "final"}) EXPECT_TRUE(j.contains(k)) << k;
  for (const char* k : {"params", "rmse_Nm", "heldout_rmse_Nm", "bic"}) EXPECT_TRUE(j["base"].contains(k)) << k;
  for (const char* k : {"params", "rmse_Nm", "heldout_rmse_Nm"}) EXPECT_TRUE(j["final"].contains(k)) << k;
  EXPECT_TRUE(j["base"]["params"].contains("M_acc"));
  ASSERT_FALSE(j["findings"].empty());
  for (const char* k : {"effect", "confidence", "where", "explanation", "params", "rmse_before_Nm",
                        "rmse_after_Nm", "heldout_rmse_before_Nm", "heldout_rmse_after_Nm"})
    EXPECT_TRUE(j["findings"][0].contains(k)) << k;
  EXPECT_EQ(j["findings"][0]["effect"], "gravity");
}

TEST(Discover, ForwardViewNeedsAPositiveInertia) {
  // Driven by the measured torque, M·θ̈ = τ − the model's other terms cannot
  // be integrated without a positive M: the view says "not available".
  fit::FitData d = with_effect(7, nullptr);
  const DiscrepancyResult r = discover(d);
  EXPECT_TRUE(std::isfinite(r.base.forward_rmse_rad));
  EXPECT_GT(r.base.forward_rmse_rad, 0.0);
  for (double& tau : d.torque) tau = -tau;  // the fit's M comes out negative
  const DiscrepancyResult flipped = discover(d);
  EXPECT_TRUE(std::isnan(flipped.base.forward_rmse_rad)) << to_json(flipped);
}

TEST(Discover, NamesAnEndstopAtTheExtremesOfTheTravel) {
  // Stops at ±3.6 rad of the ±4 rad sweep, 20 N·m/rad (validation-data units:
  // its noise SD is 1.15 N·m): only the extremes see them.
  model::Walls<double> stop;
  stop.lo = -3.6, stop.hi = 3.6, stop.K = 20.0;
  const DiscrepancyResult r = discover(with_effect(8, [&](const fit::FitData& d, std::size_t i) {
    return stop.torque(d.theta[i], d.omega[i]);
  }));
  ASSERT_FALSE(r.findings.empty()) << to_json(r);
  const Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, EffectId::Endstop) << to_json(r);
  EXPECT_NEAR(param(f, "position_rad"), 3.6, 0.25);
  EXPECT_GT(param(f, "stiffness_Nm_per_rad"), 10.0);
  EXPECT_LT(f.heldout_rmse_after_Nm, 0.9 * f.heldout_rmse_before_Nm);
  // A mechanical stop climbs on: no torque it tops out at.
  for (const auto& [name, value] : f.params) EXPECT_NE(name, "max_torque_Nm") << value;
}

TEST(Discover, NamesAWallThatTopsOutAndTheTorqueItHolds) {
  // A rendered wall: 20 N·m/rad beyond ±3 rad of the ±4 rad sweep, holding
  // at 4 N·m (the validation data's units; its detents are 0.9, its noise SD
  // 1.15), 0.2 rad in.
  model::Walls<double> wall;
  wall.lo = -3.0, wall.hi = 3.0, wall.K = 20.0, wall.limit = 4.0;
  const DiscrepancyResult r = discover(with_effect(9, [&](const fit::FitData& d, std::size_t i) {
    return wall.torque(d.theta[i], d.omega[i]);
  }));
  ASSERT_FALSE(r.findings.empty()) << to_json(r);
  const Finding& f = r.findings.front();
  EXPECT_EQ(f.effect, EffectId::Endstop) << to_json(r);
  EXPECT_NEAR(param(f, "position_rad"), 3.0, 0.1);
  EXPECT_NEAR(param(f, "max_torque_Nm"), 4.0, 0.4);
  EXPECT_GT(param(f, "stiffness_Nm_per_rad"), 8.0);
  EXPECT_NE(f.explanation.find("holds there"), std::string::npos) << f.explanation;
  EXPECT_LT(f.heldout_rmse_after_Nm, 0.8 * f.heldout_rmse_before_Nm);
  // The knob's own detents (5 per revolution) are not taken for anything else.
  for (const auto& [name, value] : r.final_model.params) {
    if (name == "P_pos") {
      EXPECT_NEAR(1.0 / std::abs(value), 5.0, 0.1) << to_json(r);
    }
  }
}

}  // namespace
}  // namespace knoblab::discovery
