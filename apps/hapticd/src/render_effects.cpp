#include "knoblab/hapticd/render_effects.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <nlohmann/json.hpp>
#include <string>

#include "short_number.hpp"

namespace knoblab::hapticd {

namespace {

using nlohmann::json;

double get(const json& obj, const char* key, double fallback) {
  return obj.contains(key) ? obj.at(key).get<double>() : fallback;
}

}  // namespace

model::EffectSet<double> effects_from_args(const json& a) {
  // The effect table's names (model/effect_table.hpp), as the schema has them.
  model::EffectSet<double> e;
  if (a.contains("offset")) e.offset.tau0 = get(a.at("offset"), "offset_Nm", 0.0);
  if (a.contains("gravity"))
    e.gravity = {get(a.at("gravity"), "amplitude_Nm", 0.0), get(a.at("gravity"), "phase_rad", 0.0)};
  if (a.contains("spring")) {
    const json& s = a.at("spring");
    e.spring.K = get(s, "stiffness_Nm_per_rad", 0.0);
    e.spring.K3 = get(s, "cubic_Nm_per_rad3", 0.0);
    e.spring.theta0 = get(s, "centre_rad", 0.0);
  }
  if (a.contains("periodic_torque")) {
    for (const json& p : a.at("periodic_torque")) {
      if (e.periodic_count == e.periodic.size()) break;  // the schema allows no more
      model::Detents<double>& d = e.periodic[e.periodic_count++];
      d.A = get(p, "amplitude_Nm", 0.0);
      d.P = get(p, "period_rad", 2.0 * std::numbers::pi) / (2.0 * std::numbers::pi);  // A·sin(θ/P + S)
      d.S = get(p, "phase_rad", 0.0);
    }
  }
  if (a.contains("detent_shape")) {
    const json& s = a.at("detent_shape");
    for (std::size_t k = 0; k < e.detent_a.size(); ++k) {
      e.detent_a[k] = get(s, ("a" + std::to_string(k + 2) + "_Nm").c_str(), 0.0);
      e.detent_b[k] = get(s, ("b" + std::to_string(k + 2) + "_Nm").c_str(), 0.0);
    }
  }
  if (a.contains("stribeck"))
    e.stribeck = {get(a.at("stribeck"), "static_excess_Nm", 0.0), get(a.at("stribeck"), "stribeck_velocity_rad_s", 1.0)};
  if (a.contains("nonlinear_damping"))
    e.damping = {get(a.at("nonlinear_damping"), "coefficient", 0.0), get(a.at("nonlinear_damping"), "exponent", 2.0)};
  if (a.contains("endstop")) {
    const json& w = a.at("endstop");
    const double at = get(w, "position_rad", 0.0);
    e.walls = {-at, at, get(w, "stiffness_Nm_per_rad", 0.0), get(w, "damping_Nm_s_per_rad", 0.0),
               get(w, "max_torque_Nm", std::numeric_limits<double>::infinity())};
  }
  return e;
}

std::optional<ParamProblem> effects_problem(const model::EffectSet<double>& e, const SafetyLimits& limits) {
  using detail::short_number;
  const auto beyond = [&](const std::string& key, double torque) -> std::optional<ParamProblem> {
    if (!std::isfinite(torque)) return ParamProblem{key, key + " is not a finite number"};
    if (std::abs(torque) <= limits.torque_limit_Nm) return std::nullopt;
    return ParamProblem{key, key + " = " + short_number(torque * 1e3) +
                                 " mN·m is beyond the device's torque limit of " +
                                 short_number(limits.torque_limit_Nm * 1e3) + " mN·m"};
  };
  if (auto b = beyond("effects.offset.offset_Nm", e.offset.tau0)) return b;
  if (auto b = beyond("effects.gravity.amplitude_Nm", e.gravity.A)) return b;
  for (std::size_t i = 0; i < e.periodic_count; ++i)
    if (auto b = beyond("effects.periodic_torque[" + std::to_string(i) + "].amplitude_Nm", e.periodic[i].A)) return b;
  for (std::size_t k = 0; k < e.detent_a.size(); ++k)
    if (auto b = beyond("effects.detent_shape.a" + std::to_string(k + 2) + "_Nm", std::hypot(e.detent_a[k], e.detent_b[k])))
      return b;
  if (auto b = beyond("effects.stribeck.static_excess_Nm", e.stribeck.excess)) return b;
  if (std::isfinite(e.walls.limit))
    if (auto b = beyond("effects.endstop.max_torque_Nm", e.walls.limit)) return b;
  // The rest grow with the motion; the supervisor's torque limit clips them.
  return std::nullopt;
}

}  // namespace knoblab::hapticd
