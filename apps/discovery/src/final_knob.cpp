// The final model's terms under the simulator's effect names, and the model
// file that carries them (docs/discrepancy.md, "Model file").
#include "final_knob.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "knoblab/fit/render_model.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::discovery {

namespace detail {

namespace {

constexpr double kPi = std::numbers::pi;

// A·sin(θ/P + S) with P < 0 is −A·sin(θ/|P| − S): the period positive, as
// the simulator and the renderer take it.
Params periodic(const char* amplitude, const char* period, const char* phase, double A, double P, double S) {
  if (P < 0) {
    A = -A;
    P = -P;
    S = -S;
  }
  return {{amplitude, A}, {period, P}, {phase, S}};
}

// One effect's parameters under `knoblab simulate --effects` names.
Params simulator_params(const ActiveEffect& e) {
  const auto& q = e.params;
  switch (e.id) {
    case EffectId::Offset: return {{"tau0", q[0]}};
    case EffectId::Gravity: return {{"A", q[0]}, {"phase", q[1]}};
    case EffectId::Spring: return {{"K", q[0]}, {"K3", q[1]}, {"theta0", e.setting}};
    case EffectId::PeriodicTorque: return periodic("A", "P", "S", q[0], q[1], q[2]);
    case EffectId::DetentShape: {
      Params p;
      for (std::size_t k = 0; k + 2 <= kShapeHarmonics; ++k) {
        p.emplace_back("a" + std::to_string(k + 2), q[2 * k]);
        p.emplace_back("b" + std::to_string(k + 2), q[2 * k + 1]);
      }
      return p;
    }
    case EffectId::Stribeck: return {{"excess", q[0]}, {"v_s", std::abs(q[1])}};
    case EffectId::NonlinearDamping: return {{"c", q[0]}, {"p", q[1]}};
    case EffectId::PositionFriction: return periodic("depth", "P", "phase", q[0], q[1], q[2]);
    case EffectId::Drift: return {{"rate", q[0]}, {"t0", e.setting}};
    case EffectId::TimeDelay: return {{"delay", e.setting}};
    case EffectId::Saturation: return {{"limit", e.setting}};
    case EffectId::Backlash: return {{"width", e.setting}};
    case EffectId::Hysteresis: return {{"presliding", e.setting}};
    case EffectId::Endstop: return {{"position", e.setting}, {"stiffness", q[0]}};
    case EffectId::Compliance: return {{"stiffness", e.setting}, {"damping", e.lag_s * e.setting}};
  }
  return {};
}

}  // namespace

FinalKnob final_knob_of(const ExtendedModel& m, const std::optional<fit::StickBand>& stick) {
  FinalKnob k;
  k.params = m.base;
  k.detents = m.base_fitted.size() > model::kA_pos && m.base_fitted[model::kA_pos];
  k.stick = stick;
  for (const ActiveEffect& e : m.effects) k.effects.push_back({e.id, simulator_params(e)});
  if (k.params[model::kA_pos] < 0) {  // half a period on: sin(k(φ + π)) = (−1)^k sin(kφ)
    k.params[model::kA_pos] = -k.params[model::kA_pos];
    k.params[model::kS_pos] = std::remainder(k.params[model::kS_pos] + kPi, 2 * kPi);
    for (EffectTerm& t : k.effects) {
      if (t.effect != EffectId::DetentShape) continue;
      for (auto& [name, value] : t.params)
        if ((name[1] - '0') % 2 == 1) value = -value;  // a3, b3
    }
  }
  return k;
}

}  // namespace detail

std::string model_file_json(const DiscrepancyResult& r, std::span<const double> omega, const std::string& input) {
  using nlohmann::ordered_json;
  const FinalKnob& k = r.final_knob;
  ordered_json params = ordered_json::object();
  for (std::size_t i = 0; i < k.params.size() && i < model::kThesisParamCount; ++i)
    params[std::string(model::kThesisParamNames[i])] = k.params[i];
  ordered_json stick = nullptr;
  if (k.stick) stick = {{"dv", k.stick->dv}, {"D_neg", k.stick->D_neg}, {"D_pos", k.stick->D_pos}};
  ordered_json effects = ordered_json::array();
  for (const EffectTerm& t : k.effects) {
    ordered_json p = ordered_json::object();
    for (const auto& [name, value] : t.params) p[name] = value;
    effects.push_back({{"effect", std::string(effect_name(t.effect))}, {"params", p}});
  }
  // Eq. 14 of the base, as a fit's render model is reduced.
  fit::FitResult base;
  base.model = fit::ModelKind::Thesis6;
  base.names = fit::param_names(base.model);
  base.params = k.params;
  base.detents = k.detents;
  base.stick = k.stick;
  const ordered_json render = ordered_json::parse(fit::to_json(fit::reduce_to_render(base, omega)));
  ordered_json findings = ordered_json::array();
  for (const Finding& f : r.findings) findings.push_back(std::string(effect_name(f.effect)));
  const ordered_json j = {{"model", "thesis6"},
                          {"params", params},
                          {"stick", stick},
                          {"effects", effects},
                          {"render", render.at("params")},
                          {"source",
                           {{"command", "knoblab discrepancy"},
                            {"input", input},
                            {"findings", findings},
                            {"heldout_rmse_Nm", r.final_model.heldout_rmse_Nm}}}};
  return j.dump(2);
}

}  // namespace knoblab::discovery
