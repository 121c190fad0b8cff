// A model file read back and its terms fitted to a capture (knob fit
// --model FILE): the effect table's names map onto the fit's parameters and
// back, so a fit started near the truth ends at it, inside its intervals.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "effect_data.hpp"
#include "knoblab/discovery/model_file.hpp"
#include "knoblab/model/effects.hpp"
#include "knoblab/model/models.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::discovery {
namespace {

constexpr double kPi = std::numbers::pi;

double get(const Params& p, const std::string& name) {
  for (const auto& [n, v] : p)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

// The validation knob (Eq. 10) with cogging, gravity and Stribeck friction,
// written as the simulator reads a model file's effects.
FinalKnob truth() {
  FinalKnob k;
  k.params = {0.4, 1.5, 1.0, 2.0, 1.5, 1.0, 0.2, 0.9};
  k.detents = true;
  k.effects = {{EffectId::PeriodicTorque, {{"amplitude_Nm", 0.8}, {"period_rad", 2 * kPi / 7.3}, {"phase_rad", 0.5}}},
               {EffectId::Gravity, {{"amplitude_Nm", 0.6}, {"phase_rad", 0.4}}},
               {EffectId::Stribeck, {{"static_excess_Nm", 1.5}, {"stribeck_velocity_rad_s", 1.0}}}};
  return k;
}

fit::FitData recording(const FinalKnob& k) {
  return test_data::with_effect(11, [&](const fit::FitData& d, std::size_t i) {
    const Params& cog = k.effects[0].params;
    const Params& g = k.effects[1].params;
    const Params& s = k.effects[2].params;
    model::Detents<double> w;
    w.A = get(cog, "amplitude_Nm");
    w.P = get(cog, "period_rad") / (2 * kPi);
    w.S = get(cog, "phase_rad");
    return w.torque(d.theta[i]) + model::OncePerRev<double>{get(g, "amplitude_Nm"), get(g, "phase_rad")}.torque(d.theta[i]) +
           model::Stribeck<double>{get(s, "static_excess_Nm"), get(s, "stribeck_velocity_rad_s")}.torque(d.omega[i]);
  });
}

// How many half-widths `fitted` lies from `true_value`.
double half_widths(double fitted, double ci95, double true_value) { return std::abs(fitted - true_value) / ci95; }

TEST(ModelFile, AModelsTermsFittedFromNearTheTruthEndAtItInsideTheirIntervals) {
  const FinalKnob t = truth();
  FinalKnob start = t;
  for (double& p : start.params) p *= 1.1;
  start.params[model::kP_pos] = t.params[model::kP_pos] * 1.005;  // the detents' period: its own basin
  for (EffectTerm& e : start.effects)
    for (auto& [name, value] : e.params) value *= name == "period_rad" ? 1.002 : 1.15;

  const ModelFit f = fit_model(recording(t), start);
  ASSERT_EQ(f.knob.effects.size(), 3u);
  for (std::size_t i = 0; i < t.params.size(); ++i) {
    ASSERT_TRUE(std::isfinite(f.base_ci95[i])) << model::kThesisParamNames[i];
    // Four standard errors: with 15 parameters a 95 % interval alone would miss one by chance.
    EXPECT_LT(half_widths(f.knob.params[i], f.base_ci95[i], t.params[i]), 2.0) << model::kThesisParamNames[i];
  }
  for (std::size_t e = 0; e < t.effects.size(); ++e) {
    ASSERT_EQ(f.knob.effects[e].effect, t.effects[e].effect);
    for (const auto& [name, value] : t.effects[e].params) {
      const double ci = get(f.effect_ci95[e], name);
      ASSERT_TRUE(std::isfinite(ci) && ci > 0) << name;
      // Identified, not merely unrefuted: the interval a small part of the value.
      EXPECT_LT(ci, 0.25 * std::abs(value)) << effect_name(t.effects[e].effect) << "." << name;
      EXPECT_LT(half_widths(get(f.knob.effects[e].params, name), ci, value), 2.0)
          << effect_name(t.effects[e].effect) << "." << name << " = " << get(f.knob.effects[e].params, name)
          << " ± " << ci << ", truth " << value;
    }
  }
  // Near the noise: uniform, 4 N·m peak to peak (SD 1.15).
  EXPECT_LT(f.rmse_Nm, 1.2);
}

TEST(ModelFile, TheRefittedModelFileReadsBackAsTheSameTerms) {
  const ModelFit f = fit_model(recording(truth()), truth());
  const fit::FitData d = recording(truth());
  const std::string text = model_file_json(f, d.omega, "cap.csv", "start.json");
  const nlohmann::json doc = nlohmann::json::parse(text);
  EXPECT_EQ(doc.at("source").at("model"), "start.json");
  EXPECT_TRUE(doc.at("ci95").at("effects")[2].at("params").at("static_excess_Nm").is_number());
  const FinalKnob back = parse_model_file(text, "refit.json");
  ASSERT_EQ(back.params.size(), f.knob.params.size());
  for (std::size_t i = 0; i < back.params.size(); ++i) EXPECT_DOUBLE_EQ(back.params[i], f.knob.params[i]);
  ASSERT_EQ(back.effects.size(), f.knob.effects.size());
  for (std::size_t e = 0; e < back.effects.size(); ++e) {
    EXPECT_EQ(back.effects[e].effect, f.knob.effects[e].effect);
    EXPECT_EQ(back.effects[e].params, f.knob.effects[e].params);
  }
}

TEST(ModelFile, OperatorsSettingsAreHeldAndHaveNoInterval) {
  FinalKnob k = truth();
  k.effects.push_back({EffectId::Backlash, {{"width_rad", 0.01}}});
  const ModelFit f = fit_model(recording(truth()), k);
  ASSERT_EQ(f.knob.effects.size(), 4u);
  EXPECT_DOUBLE_EQ(get(f.knob.effects[3].params, "width_rad"), 0.01);
  EXPECT_TRUE(std::isnan(get(f.effect_ci95[3], "width_rad")));
}

void expect_refused(const std::string& text, const std::string& says) {
  try {
    parse_model_file(text, "knob-model.json");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("knob-model.json"), std::string::npos) << what;
    EXPECT_NE(what.find(says), std::string::npos) << what;
  }
}

TEST(ModelFile, AMalformedModelFileIsRefusedNamingTheFileAndTheField) {
  expect_refused("{\"params\": {\"M_acc\": 1e-5", "not JSON");
  expect_refused("[1, 2]", "not a JSON object");
  expect_refused(R"({"model": "render9", "params": {}})", "neither thesis6");
  expect_refused(R"({"params": {"M_acc": "heavy"}})", "'M_acc' is not a finite number");
  expect_refused(R"({"params": {"mass": 1}})", "unknown parameter 'mass' (known: M_acc");
  expect_refused(R"({"params": {}, "stick": {"dv": -1}})", "magnitudes");
  expect_refused(R"({"params": {}, "effects": [{"effect": "warp", "params": {}}]})", "effects[0]");
  expect_refused(R"({"params": {}, "effects": [{"effect": "stribeck", "params": {"static_excess_Nm": 0.001,
      "stribeck_velocity_rad_s": -2}}]})", "stribeck_velocity_rad_s");
}

TEST(ModelFile, AFitsJsonReadsAsAModelWithoutEffects) {
  const FinalKnob k = parse_model_file(R"({"model": "thesis6", "params": {"M_acc": 4e-5, "A_pos": 0.01, "P_pos": 0.08},
      "ci95": {"M_acc": [3e-5, 5e-5]}, "rmse_Nm": 0.001, "stick": {"dv": 0.2, "D_neg": 0.02, "D_pos": 0.02, "samples": 9}})",
                                       "fit.json");
  EXPECT_TRUE(k.detents);
  EXPECT_TRUE(k.effects.empty());
  ASSERT_TRUE(k.stick.has_value());
  EXPECT_DOUBLE_EQ(k.stick->dv, 0.2);
  EXPECT_DOUBLE_EQ(k.params[model::kB_vel_pos], 0.0);
}

}  // namespace
}  // namespace knoblab::discovery
