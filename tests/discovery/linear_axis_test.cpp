// Discrepancy discovery on a linear actuator's recording: the search works
// in the channel's own units (m, N) as on a rotary knob; what it says is in
// mm, N, N/m and mm per cycle, never in revolutions, degrees or mN·m, and
// its JSON says "axis": "linear". The sentences of every effect are checked
// directly (candidates.hpp, internal), the search on the thesis' validation
// data read as a linear stroke.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "findings.hpp"
#include "../../apps/discovery/src/candidates.hpp"
#include "effect_data.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/discovery/report.hpp"
#include "knoblab/model/effects.hpp"

namespace knoblab::discovery {
namespace {

using knoblab::test::param;

constexpr double kPi = std::numbers::pi;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// What a linear axis's text must never say.
void expect_linear_words(const std::string& text) {
  for (const char* rotary : {"revolution", "/rev", "°", "mN·m", "rad", "θ", " torque"})
    EXPECT_FALSE(contains(text, rotary)) << "'" << rotary << "' in: " << text;
}

// The thesis' validation data (±4 rad, detents 5 per revolution, noise SD
// 1.15) read as a linear actuator's, 0.05 m per radian: a ±200 mm stroke with
// detents every 63 mm, the same forces in N; `extra` added to the force.
fit::FitData linear_stroke(std::uint64_t seed, const std::function<double(double x)>& extra) {
  constexpr double k = 0.05;  // m per rad
  fit::FitData d = test_data::with_effect(seed, nullptr);
  for (std::size_t i = 0; i < d.size(); ++i) {
    d.theta[i] *= k, d.omega[i] *= k, d.alpha[i] *= k;
    d.torque[i] += extra(d.theta[i]);
  }
  d.axis = fit::Axis::Linear;
  return d;
}

// A base model with detents every 6.28 mm (P = 1 mm per radian of phase).
detail::ExtendedModel base_with_detents() {
  detail::ExtendedModel m;
  m.base = {0.8, 1.5, 1.0, 2.0, 1.5, 1.0, 1e-3, 0.9};
  m.base_fitted.assign(m.base.size(), true);
  return m;
}

// Each effect with values a linear actuator might have (SI: m, N).
std::vector<detail::ActiveEffect> every_effect() {
  using E = EffectId;
  std::vector<detail::ActiveEffect> v = {
      {E::Offset, {0.3}, 0.0},
      {E::Gravity, {0.5, 0.1}, 0.0},
      {E::Spring, {400.0, 2e5, 0.002}, 0.0},
      {E::PeriodicTorque, {0.4, 2.5e-3 / (2 * kPi), 0.3}, 0.0},
      {E::PeriodicTorque, {0.4, 1e-3 / 3.0, 0.3}, 0.0},  // the detents' 3rd harmonic
      {E::DetentShape, {0.1, 0.0, 0.05, 0.02, 0.0, 0.01}, 0.0},
      {E::Stribeck, {0.2, 0.004}, 0.0},
      {E::NonlinearDamping, {3.0, 2.0}, 0.0},
      {E::PositionFriction, {0.1, 0.02 / (2 * kPi), 0.0}, 0.0},
      {E::Drift, {0.01}, 4.0},
      {E::TimeDelay, {}, 5e-4},
      {E::Saturation, {}, 20.0},
      {E::Backlash, {}, 1.2e-4},
      {E::Hysteresis, {}, 2e-5},
      {E::Endstop, {1e4}, 0.19},
      {E::Compliance, {}, 2e5},
  };
  v.back().lag_s = 2e-4;
  return v;
}

TEST(LinearSentences, EveryEffectIsToldWithoutRevolutionsDegreesOrTorques) {
  const detail::ExtendedModel m = base_with_detents();
  for (const bool reverses : {true, false}) {
    const detail::Motion motion{reverses, "t 0.1–2 s, x −12…40 mm", fit::Axis::Linear};
    for (const detail::ActiveEffect& e : every_effect()) {
      const detail::Explanation ex = detail::explain(e, m, motion);
      SCOPED_TRACE(std::string(effect_name(e.id)));
      EXPECT_FALSE(ex.sentence.empty());
      expect_linear_words(ex.where);
      expect_linear_words(ex.sentence);
    }
  }
}

TEST(LinearSentences, ASpringAndAPeriodicForceAreToldInNewtonsPerMetreMillimetresAndMillimetresPerCycle) {
  const detail::ExtendedModel m = base_with_detents();
  const detail::Motion motion{true, "", fit::Axis::Linear};
  const auto spring = detail::explain({EffectId::Spring, {400.0, 0.0, 0.002}, 0.0}, m, motion);
  EXPECT_EQ(spring.where, "over position, proportional to position");
  EXPECT_TRUE(contains(spring.sentence, "400 N/m")) << spring.sentence;
  EXPECT_TRUE(contains(spring.sentence, "about 2 mm")) << spring.sentence;
  const auto periodic = detail::explain({EffectId::PeriodicTorque, {0.4, 2.5e-3 / (2 * kPi), 0.3}, 0.0}, m, motion);
  EXPECT_EQ(periodic.where, "over position, 2.5 mm per cycle");
  EXPECT_TRUE(contains(periodic.sentence, "position-periodic force at 2.5 mm per cycle, 0.4 N,")) << periodic.sentence;
  const auto play = detail::explain({EffectId::Backlash, {}, 1.2e-4}, m, motion);
  EXPECT_TRUE(contains(play.sentence, "for 0.12 mm of travel: backlash (lost motion) of 120 µm")) << play.sentence;
}

TEST(LinearSentences, ARotaryAxisKeepsDegreesMilliNewtonMetresAndCyclesPerRevolution) {
  detail::ExtendedModel m = base_with_detents();
  m.base[model::kP_pos] = 1.0 / 12;
  const detail::Motion motion{true, "", fit::Axis::Rotary};
  const auto periodic = detail::explain({EffectId::PeriodicTorque, {0.001, 1.0 / 17.3, 0.3}, 0.0}, m, motion);
  EXPECT_EQ(periodic.where, "over position, 17.3 cycles/rev");
  EXPECT_TRUE(contains(periodic.sentence, "position-periodic torque at 17.3 cycles per revolution (period 20.8°), 1 mN·m"))
      << periodic.sentence;
  const auto gravity = detail::explain({EffectId::Gravity, {0.002, 0.1}, 0.0}, m, motion);
  EXPECT_TRUE(contains(gravity.sentence, "repeats once per revolution with 2 mN·m amplitude")) << gravity.sentence;
}

TEST(LinearDiscovery, GravityIsNoCandidateOnALinearAxis) {
  const auto has_gravity = [](const std::vector<EffectId>& v) {
    return std::find(v.begin(), v.end(), EffectId::Gravity) != v.end();
  };
  EXPECT_FALSE(has_gravity(implemented_effects(fit::Axis::Linear)));
  EXPECT_TRUE(has_gravity(implemented_effects(fit::Axis::Rotary)));
  EXPECT_EQ(implemented_effects(fit::Axis::Linear).size() + 1, implemented_effects().size());
}

TEST(LinearDiscovery, ASpringAndAPeriodicForceAreFoundAndToldInLinearUnits) {
  // 10 N/m about the stroke's middle (±2 N at its ends) and 1 N every 27.8 mm
  // (11.3 times the detents' frequency), beside the noise's 1.15 N.
  const double period = 2 * kPi * 0.05 / 11.3;
  const fit::FitData d = linear_stroke(4, [&](double x) { return 10.0 * x + 1.0 * std::sin(2 * kPi * x / period + 0.5); });
  DiscrepancyOptions opt;
  opt.min_reported_gain = 0.0;
  const DiscrepancyResult r = discover(d, opt);
  std::vector<EffectId> found;
  for (const Finding& f : r.findings) {
    found.push_back(f.effect);
    expect_linear_words(f.where);
    expect_linear_words(f.explanation);
    EXPECT_TRUE(contains(f.explanation, " N")) << f.explanation;
  }
  ASSERT_EQ(found.size(), 2u) << to_json(r);
  EXPECT_TRUE(std::find(found.begin(), found.end(), EffectId::Spring) != found.end()) << to_json(r);
  EXPECT_TRUE(std::find(found.begin(), found.end(), EffectId::PeriodicTorque) != found.end()) << to_json(r);
  for (const Finding& f : r.findings) {
    if (f.effect == EffectId::Spring) {
      EXPECT_TRUE(contains(f.explanation, " N/m")) << f.explanation;
    }
    if (f.effect == EffectId::PeriodicTorque) {
      EXPECT_TRUE(contains(f.explanation, " mm per cycle")) << f.explanation;
      EXPECT_NEAR(param(f, "period_rad"), period, 0.01 * period) << to_json(r);  // SI: m
    }
  }
  const auto j = nlohmann::json::parse(to_json(r));
  EXPECT_EQ(j["axis"], "linear");
  EXPECT_EQ(j.begin().key(), "axis");  // first: read before the numbers
}

TEST(LinearDiscovery, TheReportsAxesAreInMillimetresAndNewtons) {
  const fit::FitData d = linear_stroke(2, [](double x) { return 10.0 * x; });
  const DiscrepancyResult r = discover(d);
  const auto figures = discrepancy_figures(d, r);
  for (const auto& [name, f] : figures) {
    SCOPED_TRACE(name);
    if (name == "residual_position") {
      EXPECT_EQ(f.x_column, "position_mm");
      EXPECT_EQ(f.panels.front().xlabel, "position x (mm)");
    }
    if (name == "residual_velocity") {
      EXPECT_EQ(f.x_column, "velocity_mm_per_s");
    }
    if (name.starts_with("residual_")) {
      EXPECT_EQ(f.y_column, "residual_N");
      EXPECT_EQ(f.panels.front().ylabel, "residual (N)");
    }
    expect_linear_words(f.title + f.subtitle);
    for (const auto& p : f.panels) expect_linear_words(p.heading + p.xlabel + p.ylabel);
    for (const auto& row : f.text.table)
      for (const std::string& cell : row) expect_linear_words(cell);
    for (const std::string& text : f.text.paragraphs) expect_linear_words(text);
    for (const std::string& note : f.text.notes) expect_linear_words(note);
  }
}

}  // namespace
}  // namespace knoblab::discovery
