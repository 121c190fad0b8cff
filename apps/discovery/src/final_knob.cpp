// The final model's terms under the effect table's names (those discrepancy
// reports and simulate --effects takes), and the model
// file that carries them (docs/discrepancy.md, "Model file").
#include "final_knob.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "candidates.hpp"
#include "knoblab/fit/render_model.hpp"
#include "knoblab/model/effect_table.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::discovery {

namespace detail {

namespace {

constexpr double kPi = std::numbers::pi;

// a3_Nm, b3_Nm: a detent harmonic of odd order.
bool odd_harmonic(const std::string& name) {
  return name.size() > 1 && (name[0] == 'a' || name[0] == 'b') && name[1] >= '0' && name[1] <= '9' &&
         (name[1] - '0') % 2 == 1;
}

}  // namespace

// As discrepancy reports them, without what is derived beside them, and no
// alternatives beside the parameters they replace: as
// model::effect_from_params reads them back.
Params settable_params(const ActiveEffect& e, const ExtendedModel& m) {
  const model::EffectRow& row = model::effect_row(e.id);
  Params out;
  for (auto& [name, value] : report_params(e, m)) {
    const model::EffectParam* p = row.param(name);
    if (p && p->settable() && p->role != model::Role::Alternative) out.emplace_back(name, value);
  }
  return out;
}

FinalKnob final_knob_of(const ExtendedModel& m, const std::optional<fit::StickBand>& stick) {
  FinalKnob k;
  k.params = m.base;
  k.detents = m.has_detents();
  k.stick = stick;
  for (const ActiveEffect& e : m.effects) k.effects.push_back({e.id, settable_params(e, m)});
  if (k.params[model::kA_pos] < 0) {  // half a period on: sin(k(φ + π)) = (−1)^k sin(kφ)
    k.params[model::kA_pos] = -k.params[model::kA_pos];
    k.params[model::kS_pos] = std::remainder(k.params[model::kS_pos] + kPi, 2 * kPi);
    for (EffectTerm& t : k.effects) {
      if (t.effect != EffectId::DetentShape) continue;
      for (auto& [name, value] : t.params)
        if (odd_harmonic(name)) value = -value;
    }
  }
  return k;
}


ExtendedModel extended_of(const FinalKnob& k) {
  ExtendedModel m;
  m.base = k.params;
  m.base.resize(model::kThesisParamCount, 0.0);
  m.base_fitted.assign(model::kThesisParamCount, true);
  if (!k.detents) {
    for (const std::size_t i : {model::kA_pos, model::kP_pos, model::kS_pos}) m.base_fitted[i] = false;
    m.base[model::kA_pos] = 0.0;
  }
  if (k.stick) {
    m.stick_band = k.stick->dv;
    m.breakaway = std::max(k.stick->D_pos, k.stick->D_neg);
  }
  for (const EffectTerm& t : k.effects) {
    const model::EffectSpec spec = model::effect_from_params(effect_name(t.effect), t.params);
    const auto v = [&](std::string_view name) { return spec.value(name); };
    ActiveEffect e;
    e.id = t.effect;
    switch (t.effect) {
      case EffectId::Offset: e.params = {v("offset_Nm")}; break;
      case EffectId::Gravity: e.params = {v("amplitude_Nm"), v("phase_rad")}; break;
      case EffectId::Spring:
        e.params = {v("stiffness_Nm_per_rad"), v("cubic_Nm_per_rad3"), v("centre_rad")};
        break;
      case EffectId::PeriodicTorque:
        e.params = {v("amplitude_Nm"), v("period_rad") / (2 * kPi), v("phase_rad")};
        break;
      case EffectId::PositionFriction:
        e.params = {v("depth_Nm"), v("period_rad") / (2 * kPi), v("phase_rad")};
        break;
      case EffectId::DetentShape:
        e.params = {v("a2_Nm"), v("b2_Nm"), v("a3_Nm"), v("b3_Nm"), v("a4_Nm"), v("b4_Nm")};
        break;
      case EffectId::Stribeck: e.params = {v("static_excess_Nm"), v("stribeck_velocity_rad_s")}; break;
      case EffectId::NonlinearDamping: e.params = {v("coefficient"), v("exponent")}; break;
      case EffectId::Drift:
        e.params = {v("rate_Nm_per_s")};
        e.setting = v("t0_s");
        break;
      case EffectId::TimeDelay: e.setting = v("delay_s"); break;
      case EffectId::Saturation: e.setting = v("limit_Nm"); break;
      case EffectId::Backlash: e.setting = v("width_rad"); break;
      case EffectId::Hysteresis: e.setting = v("presliding_angle_rad"); break;
      case EffectId::Endstop:
        e.params = {v("stiffness_Nm_per_rad")};
        if (std::isfinite(v("max_torque_Nm"))) e.params.push_back(v("max_torque_Nm"));  // a wall that tops out
        e.setting = v("position_rad");
        break;
      case EffectId::Compliance: {
        // Against the knob's inertia as this model has it, as discovery
        // reports the ringing (report_params).
        const double J = std::abs(m.base[model::kM_acc]);
        double k_c = v("stiffness_Nm_per_rad");
        if (std::isnan(k_c)) k_c = J * std::pow(2 * kPi * v("frequency_hz"), 2);
        double c = v("damping_Nm_s_per_rad");
        if (std::isnan(c) && !std::isnan(v("zeta"))) c = 2 * v("zeta") * std::sqrt(k_c * J);
        e.setting = k_c;
        e.lag_s = std::isnan(c) || !(k_c > 0) ? 0.0 : c / k_c;
        break;
      }
    }
    for (const double p : e.params)
      if (!std::isfinite(p))
        throw std::invalid_argument(std::string(effect_name(t.effect)) + ": a parameter has no value");
    m.effects.push_back(std::move(e));
  }
  return m;
}

nlohmann::ordered_json model_file_fields(const FinalKnob& k, std::span<const double> omega) {
  using nlohmann::ordered_json;
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
  return {{"model", "thesis6"}, {"params", params}, {"stick", stick}, {"effects", effects},
          {"render", render.at("params")}};
}

}  // namespace detail

std::string model_file_json(const DiscrepancyResult& r, std::span<const double> omega, const std::string& input) {
  using nlohmann::ordered_json;
  ordered_json j = detail::model_file_fields(r.final_knob, omega);
  ordered_json findings = ordered_json::array();
  for (const Finding& f : r.findings) findings.push_back(std::string(effect_name(f.effect)));
  j["source"] = {{"command", "knoblab discrepancy"},
                 {"input", input},
                 {"findings", findings},
                 {"heldout_rmse_Nm", r.final_model.heldout_rmse_Nm}};
  return j.dump(2);
}

}  // namespace knoblab::discovery
