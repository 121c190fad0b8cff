// The final model as a knob (DiscrepancyResult::final_knob) and its model
// file: the kept effects under the effect table's names must give
// the final model's torque, and the file must carry what its readers need.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "effect_data.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/model/effect_json.hpp"
#include "knoblab/model/effect_table.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::discovery {
namespace {

using test_data::with_effect;

double get(const Params& p, const std::string& name) {
  for (const auto& [n, v] : p)
    if (n == name) return v;
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

// The knob's torque from its Eq. 6 parameters and its effects as the
// simulator reads them (periodic_torque: A·sin(2πθ/period + φ); gravity: A·sin(θ + φ)).
double knob_torque(const FinalKnob& k, double theta, double omega, double alpha) {
  double tau = model::ThesisModel<double>::from_params(k.params.data()).torque({theta, omega, alpha});
  for (const EffectTerm& e : k.effects) {
    if (e.effect == EffectId::PeriodicTorque) {
      model::Detents<double> w;
      w.A = get(e.params, "amplitude_Nm");
      w.P = get(e.params, "period_rad") / (2 * std::numbers::pi);
      w.S = get(e.params, "phase_rad");
      tau += w.torque(theta);
    } else if (e.effect == EffectId::Gravity) {
      tau += model::OncePerRev<double>{get(e.params, "amplitude_Nm"), get(e.params, "phase_rad")}.torque(theta);
    } else {
      ADD_FAILURE() << "unexpected effect " << effect_name(e.effect);
    }
  }
  return tau;
}

TEST(FinalKnob, ItsTermsUnderTheTablesNamesGiveTheFinalModelsTorque) {
  const model::Detents<double> a{0.6, 1.0 / 11.3, 0.5}, b{0.5, 1.0 / 17.9, -1.0};
  const fit::FitData d = with_effect(6, [&](const fit::FitData& x, std::size_t i) {
    return a.torque(x.theta[i]) + b.torque(x.theta[i]);
  });
  DiscrepancyOptions opt;
  opt.min_reported_gain = 0.0;
  const DiscrepancyResult r = discover(d, opt);
  ASSERT_EQ(r.final_knob.effects.size(), r.findings.size());
  ASSERT_GE(r.final_knob.effects.size(), 2u) << to_json(r);
  for (const EffectTerm& e : r.final_knob.effects) {
    if (e.effect != EffectId::PeriodicTorque) continue;
    EXPECT_GT(get(e.params, "period_rad"), 0.0);  // the simulator's period is positive
    // Only parameters simulate --effects takes (cycles_per_rev is derived).
    EXPECT_NO_THROW(model::effect_from_params("periodic_torque", e.params));
    for (const auto& [name, value] : e.params) EXPECT_NE(name, "cycles_per_rev");
  }
  // The trace's training rows: measured − after is the final model's torque.
  std::map<double, std::size_t> row_at;
  for (std::size_t i = 0; i < d.size(); ++i) row_at[d.t[i]] = i;
  std::size_t checked = 0;
  for (std::size_t k = 0; k < r.trace.size(); ++k) {
    if (r.trace.heldout[k]) continue;
    const std::size_t i = row_at.at(r.trace.t[k]);
    EXPECT_NEAR(knob_torque(r.final_knob, d.theta[i], d.omega[i], d.alpha[i]), r.trace.torque[k] - r.trace.after[k],
                1e-9 * (1.0 + std::abs(r.trace.torque[k])))
        << "row " << i;
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
}

TEST(FinalKnob, TentativeFindingsLeaveItTheBase) {
  const model::Detents<double> cogging{0.8, 1.0 / 11.3, 0.5};
  const DiscrepancyResult r = discover(with_effect(4, [&](const fit::FitData& x, std::size_t i) {
    return cogging.torque(x.theta[i]);
  }));
  ASSERT_FALSE(r.tentative.empty()) << to_json(r);
  EXPECT_TRUE(r.final_knob.effects.empty());
  for (std::size_t k = 0; k < model::kThesisParamCount; ++k)
    EXPECT_EQ(r.final_knob.params[k], r.base.params[k].second) << r.base.params[k].first;
}

TEST(ModelFile, HoldsTheBaseItsEffectsAndTheRenderModel) {
  const fit::FitData d = with_effect(3, [](const fit::FitData& x, std::size_t i) { return 1.2 * std::sin(x.theta[i] + 0.4); });
  const DiscrepancyResult r = discover(d);
  ASSERT_FALSE(r.findings.empty()) << to_json(r);
  const auto j = nlohmann::json::parse(model_file_json(r, d.omega, "validation.csv"));
  EXPECT_EQ(j.at("model"), "thesis6");
  for (const auto name : model::kThesisParamNames) EXPECT_TRUE(j.at("params").contains(std::string(name))) << name;
  ASSERT_EQ(j.at("effects").size(), 1u);
  EXPECT_EQ(j.at("effects")[0].at("effect"), "gravity");
  EXPECT_NEAR(std::abs(j.at("effects")[0].at("params").at("amplitude_Nm").get<double>()), 1.2, 0.25);
  EXPECT_TRUE(j.at("effects")[0].at("params").contains("phase_rad"));
  // Read back as simulate reads a model file's effects.
  EXPECT_NO_THROW(model::effect_from_json(j.at("effects")[0]));
  // Eq. 14 of the base, as knoblab fit --render-model writes it.
  for (const char* k : {"M_acc", "B_vel", "A_pos", "P_pos"}) EXPECT_TRUE(j.at("render").contains(k)) << k;
  EXPECT_GT(j.at("render").at("B_vel").get<double>(), 0.0);
  EXPECT_EQ(j.at("render").at("A_pos").get<double>(), std::abs(j.at("params").at("A_pos").get<double>()));
  EXPECT_EQ(j.at("source").at("input"), "validation.csv");
}

}  // namespace
}  // namespace knoblab::discovery
