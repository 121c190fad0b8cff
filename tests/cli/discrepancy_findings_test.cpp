// What discrepancy's findings say of captures of the simulated knob holds
// together: a coupling that does not ring is not said to, a recording that
// turns one way only is not said to reverse, successive findings' figures
// chain, and a finding's params go back into the simulator as they are.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>

#include "findings.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/model/effect_json.hpp"
#include "knoblab/sim/presets.hpp"
#include "simulation.hpp"

namespace knoblab::cli {
namespace {

using knoblab::test::finding;
using knoblab::test::param;

using discovery::DiscrepancyResult;
using discovery::EffectId;
using discovery::Finding;

SimulationResult simulated(const std::string& knob, const std::string& effects, double seconds = 8.0,
                           std::optional<model::SweptSine> sweep = std::nullopt) {
  SimulationRequest req;
  req.knob_name = knob;
  req.knob = *sim::presets::knob(knob);
  req.seconds = seconds;
  req.effects = model::parse_effect_specs(effects);
  if (sweep) req.stimulus = *sweep;
  return simulate(req, nullptr);
}

DiscrepancyResult discover_with(const std::string& knob, const std::string& effects,
                                std::optional<model::SweptSine> sweep = std::nullopt) {
  return discovery::discover(fit::prepare(simulated(knob, effects, 8.0, sweep).capture));
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string mNm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v * 1e3);
  return buf;
}

TEST(DiscrepancyFindings, ACouplingIsSaidToRingOnlyBelowADampingRatioOfOne) {
  // Moderate-detents through a 10 N·m/rad coupling at damping ratio 2: found
  // at 20 N·m/rad, ζ 2 (measured), overdamped. Its twist follows the torque
  // through a lag, corner k/(2π·c); nothing rings.
  const DiscrepancyResult r = discover_with("moderate-detents", "compliance:stiffness_Nm_per_rad=10,zeta=2");
  const Finding* f = finding(r, EffectId::Compliance);
  ASSERT_NE(f, nullptr) << discovery::to_json(r);
  ASSERT_GE(param(*f, "zeta"), 1.0) << discovery::to_json(r);
  for (const std::string& text : {f->where, f->explanation}) EXPECT_FALSE(contains(text, "ringing near")) << text;
  EXPECT_FALSE(contains(f->where, "(ringing)")) << f->where;
  EXPECT_TRUE(contains(f->explanation, "overdamped")) << f->explanation;
  char corner[64];
  std::snprintf(corner, sizeof corner, "corner near %.3g Hz",
                param(*f, "stiffness_Nm_per_rad") / (2 * std::numbers::pi * param(*f, "damping_Nm_s_per_rad")));
  EXPECT_TRUE(contains(f->explanation, corner)) << corner << " in " << f->explanation;

  // High-friction through 55.7 N·m/rad at the rig's damping ratio: found at
  // ζ 0.51, which rings, near its frequency with the knob's inertia.
  const DiscrepancyResult ringing = discover_with("high-friction", "compliance:stiffness_Nm_per_rad=55.7");
  const Finding* g = finding(ringing, EffectId::Compliance);
  ASSERT_NE(g, nullptr) << discovery::to_json(ringing);
  ASSERT_LT(param(*g, "zeta"), 1.0);
  char near[64];
  std::snprintf(near, sizeof near, "ringing near %.3g Hz", param(*g, "frequency_hz"));
  EXPECT_TRUE(contains(g->explanation, near)) << near << " in " << g->explanation;
  EXPECT_FALSE(contains(g->explanation, "overdamped")) << g->explanation;
}

TEST(DiscrepancyFindings, ARecordingThatTurnsOneWayOnlyIsNotSaidToReverse) {
  // θ = 3·sin(π·0.45·t²/64) over 8 s: from rest to 2.96 rad, never back.
  // Moderate-detents with 5 mrad of play: found as backlash (5.2 mrad
  // measured), which the thesis sweep shows after every reversal; here the
  // sentence says where it is instead.
  const model::SweptSine one_way{0.0, 0.45, 3.0, 8.0};
  const DiscrepancyResult r = discover_with("moderate-detents", "backlash:width_rad=0.005", one_way);
  const Finding* f = finding(r, EffectId::Backlash);
  ASSERT_NE(f, nullptr) << discovery::to_json(r);
  for (const Finding& any : r.findings) {
    for (const std::string& text : {any.where, any.explanation}) {
      EXPECT_FALSE(contains(text, "revers")) << text;
      EXPECT_FALSE(contains(text, "breakaway")) << text;
    }
  }
  EXPECT_TRUE(contains(f->where, "the recording turns one way only")) << f->where;
  EXPECT_TRUE(contains(f->explanation, "felt most at t ")) << f->explanation;

  // The same play under the thesis sweep, which reverses: said so.
  const DiscrepancyResult swept = discover_with("moderate-detents", "backlash:width_rad=0.005");
  const Finding* g = finding(swept, EffectId::Backlash);
  ASSERT_NE(g, nullptr) << discovery::to_json(swept);
  EXPECT_TRUE(contains(g->explanation, "After every reversal")) << g->explanation;
}

// Moderate-detents with a 2 mN·m torque at 17.3 cycles/rev and its torque
// channel 0.73 ms behind: two findings, the second of which (the delay)
// leaves some held-out rows undescribed. Shared by the tests below.
const DiscrepancyResult& two_findings() {
  static const DiscrepancyResult r = discover_with(
      "moderate-detents",
      "periodic_torque:amplitude_Nm=0.002,period_rad=0.36316811075498007,phase_rad=0.3;time_delay:delay_s=0.00073");
  return r;
}

TEST(DiscrepancyFindings, SuccessiveFindingsFiguresChainInTheSentencesAndTheJson) {
  const DiscrepancyResult& r = two_findings();
  ASSERT_GE(r.findings.size(), 2u) << discovery::to_json(r);
  ASSERT_NE(finding(r, EffectId::TimeDelay), nullptr) << discovery::to_json(r);
  // The delay moves some rows into the stick band: the figures are over the
  // rows every model describes, and the sentences say how many.
  EXPECT_LT(r.findings.back().heldout_rows, r.heldout_rows);
  const auto j = nlohmann::json::parse(discovery::to_json(r));
  for (std::size_t k = 0; k + 1 < r.findings.size(); ++k) {
    const Finding &a = r.findings[k], &b = r.findings[k + 1];
    EXPECT_EQ(a.heldout_rmse_after_Nm, b.heldout_rmse_before_Nm) << k;
    EXPECT_EQ(a.rmse_after_Nm, b.rmse_before_Nm) << k;
    EXPECT_EQ(a.bic_after, b.bic_before) << k;
    EXPECT_EQ(a.heldout_rows, b.heldout_rows) << k;
    EXPECT_EQ(j["findings"][k]["heldout_rmse_after_Nm"], j["findings"][k + 1]["heldout_rmse_before_Nm"]) << k;
    EXPECT_EQ(j["findings"][k]["rmse_after_Nm"], j["findings"][k + 1]["rmse_before_Nm"]) << k;
    const std::string after = "→ " + mNm(a.heldout_rmse_after_Nm) + " mN·m";
    const std::string before = "Held-out RMS " + mNm(b.heldout_rmse_before_Nm) + " →";
    EXPECT_TRUE(contains(a.explanation, after)) << after << " in " << a.explanation;
    EXPECT_TRUE(contains(b.explanation, before)) << before << " in " << b.explanation;
  }
  for (const Finding& f : r.findings) {
    const std::string rows = "over the " + std::to_string(f.heldout_rows) + " of " + std::to_string(r.heldout_rows) +
                             " held-out rows every model from the base to the last finding describes";
    EXPECT_TRUE(contains(f.explanation, rows)) << f.explanation;
  }
}

TEST(DiscrepancyFindings, AFindingsParamsGoBackIntoSimulateAsTheyAre) {
  const DiscrepancyResult& r = two_findings();
  ASSERT_FALSE(r.findings.empty()) << discovery::to_json(r);
  const auto j = nlohmann::json::parse(discovery::to_json(r));
  std::string effects;
  for (const auto& f : j["findings"]) {
    const model::EffectSpec spec = model::effect_from_json(f);
    EXPECT_EQ(spec.id(), f["effect"].get<std::string>());
    for (const auto& [name, value] : spec.params) EXPECT_EQ(value, f["params"][name].get<double>()) << name;
    effects += (effects.empty() ? "" : ";") + spec.text();
  }
  // The text reads back as the same specs, and the simulator takes them.
  const SimulationResult s = simulated("moderate-detents", effects, 1.0);
  bool recorded = false;
  for (const auto& [key, value] : s.capture.metadata) recorded = recorded || (key == "effects" && value == effects);
  EXPECT_TRUE(recorded) << effects;
}

}  // namespace
}  // namespace knoblab::cli
