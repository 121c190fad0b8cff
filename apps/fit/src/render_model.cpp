#include "knoblab/fit/render_model.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace knoblab::fit {

RenderModelFile reduce_to_render(const FitResult& r, std::span<const double> omega) {
  const model::ThesisModel<double> m = thesis_model(r);
  RenderModelFile out;
  out.M_acc = m.inertia.M;
  // B minimising Σ (friction(ω) − B·ω)² over the captured velocities.
  double num = 0.0, den = 0.0;
  for (double w : omega) {
    num += m.friction.torque(w) * w;
    den += w * w;
  }
  out.B_vel = den > 0 ? std::max(0.0, num / den) : 0.0;
  if (r.detents) {
    out.A_pos = std::abs(m.detents.A);
    out.P_pos = m.detents.P;
  }
  out.stick = r.stick;
  return out;
}

std::string to_json(const RenderModelFile& m) {
  nlohmann::ordered_json p = {
      {"M_acc", m.M_acc}, {"B_vel", m.B_vel}, {"A_pos", m.A_pos}, {"P_pos", m.P_pos}};
  if (m.stick) {
    p["dv"] = m.stick->dv;
    p["D_neg"] = m.stick->D_neg;
    p["D_pos"] = m.stick->D_pos;
  }
  nlohmann::ordered_json j = {{"model", "render4"}, {"params", p}};
  return j.dump(2) + "\n";
}

namespace {

double number(const nlohmann::json& params, const char* key, bool required, double fallback) {
  const auto it = params.find(key);
  if (it == params.end()) {
    if (required) throw std::invalid_argument(std::string("render model: missing '") + key + "'");
    return fallback;
  }
  if (!it->is_number() || !std::isfinite(it->get<double>())) {
    throw std::invalid_argument(std::string("render model: '") + key + "' must be a finite number");
  }
  return it->get<double>();
}

}  // namespace

RenderModelFile parse_render_model(const std::string& text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::invalid_argument(std::string("render model: not JSON: ") + e.what());
  }
  if (!j.is_object() || j.value("model", "") != "render4" || !j.contains("params") ||
      !j["params"].is_object()) {
    throw std::invalid_argument(
        "render model: expected {\"model\": \"render4\", \"params\": {...}}");
  }
  const nlohmann::json& p = j["params"];
  static const char* const kKeys[] = {"M_acc", "B_vel", "A_pos", "P_pos", "dv", "D_neg", "D_pos"};
  for (const auto& [key, value] : p.items()) {
    if (std::find_if(std::begin(kKeys), std::end(kKeys), [&](const char* k) { return key == k; }) ==
        std::end(kKeys)) {
      throw std::invalid_argument("render model: unknown parameter '" + key + "'");
    }
  }
  RenderModelFile m;
  m.M_acc = number(p, "M_acc", true, 0);
  m.B_vel = number(p, "B_vel", true, 0);
  m.A_pos = number(p, "A_pos", true, 0);
  m.P_pos = number(p, "P_pos", true, 1);
  const int stick_keys = int(p.contains("dv")) + int(p.contains("D_neg")) + int(p.contains("D_pos"));
  if (stick_keys != 0 && stick_keys != 3) {
    throw std::invalid_argument("render model: give all or none of dv, D_neg, D_pos");
  }
  if (stick_keys == 3) {
    m.stick = StickBand{number(p, "dv", true, 0), number(p, "D_neg", true, 0),
                        number(p, "D_pos", true, 0), 0};
  }
  return m;
}

}  // namespace knoblab::fit
