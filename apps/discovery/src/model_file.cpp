// A model file read back, and its terms fitted to another capture
// (knoblab/discovery/model_file.hpp).
#include "knoblab/discovery/model_file.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "extended_model.hpp"
#include "final_knob.hpp"
#include "knoblab/fit/covariance.hpp"
#include "knoblab/model/effect_json.hpp"
#include "knoblab/model/models.hpp"
#include "knoblab/model/quantile.hpp"

namespace knoblab::discovery {

namespace {

using nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double number_field(const json& obj, const std::string& key, const std::string& where, double fallback) {
  if (!obj.contains(key)) return fallback;
  const json& v = obj.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw std::invalid_argument(where + ": '" + key + "' is not a finite number");
  return v.get<double>();
}

void refuse_unknown(const json& obj, std::span<const std::string_view> known, const std::string& where) {
  for (const auto& [key, value] : obj.items()) {
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string list;
    for (const std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
    throw std::invalid_argument(where + ": unknown parameter '" + key + "' (known: " + list + ")");
  }
}

// The fit's rows: moving faster than the stick band and than 2 % of the
// brisk (95th-percentile) speed, evenly strided to at most kMaxRows.
constexpr std::size_t kMaxRows = 20000;
std::vector<std::size_t> moving_rows(const fit::FitData& d, double slow) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (std::abs(d.omega[i]) >= slow) rows.push_back(i);
  if (rows.size() <= kMaxRows) return rows;
  std::vector<std::size_t> strided;
  const double step = static_cast<double>(rows.size()) / static_cast<double>(kMaxRows);
  for (std::size_t k = 0; k < kMaxRows; ++k) strided.push_back(rows[static_cast<std::size_t>(static_cast<double>(k) * step)]);
  return strided;
}

// An effect's settable parameters as a function of its own continuous ones.
Params named_at(const detail::ExtendedModel& m, std::size_t e, std::span<const double> q) {
  detail::ExtendedModel probe = m;
  std::copy(q.begin(), q.end(), probe.effects[e].params.begin());
  return detail::settable_params(probe.effects[e], probe);
}

// 95 % half-widths of an effect's settable parameters by the delta method:
// G·C·Gᵀ with G the parameters' derivatives (central differences) with
// respect to the effect's own block of the covariance. Those set by a
// search (an operator's setting) have no interval: NaN.
Params effect_intervals(const detail::ExtendedModel& m, std::size_t e, std::size_t offset,
                        const fit::CovarianceEstimate& cov, std::size_t n) {
  const std::vector<double>& q = m.effects[e].params;
  const Params at = named_at(m, e, q);
  const std::size_t k = q.size();
  std::vector<std::vector<double>> G(at.size(), std::vector<double>(k, 0.0));
  for (std::size_t c = 0; c < k; ++c) {
    const double h = 1e-6 * std::max(std::abs(q[c]), 1e-9);
    std::vector<double> up = q, down = q;
    up[c] += h;
    down[c] -= h;
    const Params pu = named_at(m, e, up), pd = named_at(m, e, down);
    for (std::size_t r = 0; r < at.size(); ++r) G[r][c] = (pu[r].second - pd[r].second) / (2 * h);
  }
  Params out;
  for (std::size_t r = 0; r < at.size(); ++r) {
    double var = 0.0;
    bool depends = false;
    for (std::size_t a = 0; a < k; ++a)
      for (std::size_t b = 0; b < k; ++b) {
        var += G[r][a] * cov.covariance[(offset + a) * n + offset + b] * G[r][b];
        depends = depends || G[r][a] != 0.0;
      }
    out.emplace_back(at[r].first, depends ? cov.t95 * std::sqrt(std::max(0.0, var)) : kNaN);
  }
  return out;
}

// A render model (Eq. 14, `knoblab fit --render-model`): one viscous term
// both ways, no Coulomb level, the stick band among the parameters, and no
// detent phase (where a capture started is not the knob's).
FinalKnob render_model_knob(const json& p, const std::string& where) {
  static constexpr std::string_view kNames[] = {"M_acc", "B_vel", "A_pos", "P_pos", "S_pos", "dv", "D_neg", "D_pos"};
  refuse_unknown(p, kNames, where + ": params");
  const auto v = [&](const char* name, double fallback) { return number_field(p, name, where + ": params", fallback); };
  FinalKnob k;
  k.params.assign(model::kThesisParamCount, 0.0);
  k.params[model::kM_acc] = v("M_acc", 0.0);
  k.params[model::kB_vel_neg] = k.params[model::kB_vel_pos] = v("B_vel", 0.0);
  k.params[model::kA_pos] = v("A_pos", 0.0);
  k.params[model::kP_pos] = v("P_pos", 1.0);
  k.params[model::kS_pos] = v("S_pos", 0.0);
  k.detents = k.params[model::kA_pos] != 0.0;
  k.detent_phase_unknown = !p.contains("S_pos");
  if (p.contains("dv")) k.stick = fit::StickBand{v("dv", 0.0), v("D_neg", 0.0), v("D_pos", 0.0), 0};
  return k;
}

}  // namespace

FinalKnob parse_model_file(std::string_view json_text, std::string_view source) {
  const std::string where(source);
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(where + ": not JSON (" + e.what() + ")");
  }
  if (!doc.is_object()) throw std::invalid_argument(where + ": not a JSON object");
  if (!doc.contains("params") || !doc.at("params").is_object())
    throw std::invalid_argument(where + ": no \"params\" object");
  const json& p = doc.at("params");
  const std::string kind = doc.contains("model") && doc.at("model").is_string() ? doc.at("model").get<std::string>()
                           : doc.contains("model")                             ? doc.at("model").dump()
                                                                               : "thesis6";
  FinalKnob k;
  if (kind == "render4") return render_model_knob(p, where);
  if (kind != "thesis6")
    throw std::invalid_argument(where + ": model '" + kind +
                                "' is neither thesis6 (a model file, a fit's JSON) nor render4 (a render model)");
  refuse_unknown(p, model::kThesisParamNames, where + ": params");
  for (std::size_t i = 0; i < model::kThesisParamCount; ++i)
    k.params.push_back(number_field(p, std::string(model::kThesisParamNames[i]), where + ": params",
                                    i == model::kP_pos ? 1.0 : 0.0));
  k.detents = k.params[model::kA_pos] != 0.0;
  if (doc.contains("stick") && !doc.at("stick").is_null()) {
    const json& s = doc.at("stick");
    if (!s.is_object()) throw std::invalid_argument(where + ": \"stick\" must be an object or null");
    static constexpr std::string_view kStick[] = {"dv", "D_neg", "D_pos", "samples"};
    refuse_unknown(s, kStick, where + ": stick");
    fit::StickBand b;
    b.dv = number_field(s, "dv", where + ": stick", 0.0);
    b.D_neg = number_field(s, "D_neg", where + ": stick", 0.0);
    b.D_pos = number_field(s, "D_pos", where + ": stick", 0.0);
    if (b.dv < 0 || b.D_neg < 0 || b.D_pos < 0)
      throw std::invalid_argument(where + ": stick: dv, D_neg and D_pos are magnitudes (>= 0)");
    k.stick = b;
  }
  if (doc.contains("effects")) {
    const json& list = doc.at("effects");
    if (!list.is_array()) throw std::invalid_argument(where + ": \"effects\" must be an array");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string at = where + ": effects[" + std::to_string(i) + "]";
      try {
        const model::EffectSpec spec = model::effect_from_json(list.at(i));
        k.effects.push_back({spec.effect, spec.params});
      } catch (const std::exception& e) {
        throw std::invalid_argument(at + ": " + e.what());
      }
    }
  }
  // Every term as the fit takes it (an effect without a value it needs).
  try {
    detail::extended_of(k);
  } catch (const std::exception& e) {
    throw std::invalid_argument(where + ": " + e.what());
  }
  return k;
}

ModelFit fit_model(const fit::FitData& d, const FinalKnob& start, const fit::RunHooks& hooks) {
  const auto t0 = std::chrono::steady_clock::now();
  detail::ExtendedModel m = detail::extended_of(start);
  std::vector<double> speed(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) speed[i] = std::abs(d.omega[i]);
  m.stick_speed = std::max(0.02 * model::quantile(std::move(speed), 0.95), m.stick_band);
  const std::vector<std::size_t> rows = moving_rows(d, m.stick_speed);
  const std::size_t n = m.flat().size();
  if (rows.size() < 10 * n + 100)
    throw fit::FitDataError("too few moving samples to fit the model's " + std::to_string(n) +
                            " parameters: " + std::to_string(rows.size()));
  hooks.report("fitting the model");
  const detail::FitReport rep = detail::fit_extended(m, d, rows, 100);
  hooks.check();
  hooks.report("intervals");
  const detail::RowsJacobian rj = detail::residual_jacobian(m, d, rows);
  const std::vector<bool> fitted = m.free_mask();
  const fit::CovarianceEstimate cov = fit::covariance_from_rows(rj.residuals, rj.jacobian, n, fitted);

  ModelFit out;
  out.knob = detail::final_knob_of(m, start.stick);
  for (std::size_t i = 0; i < m.base.size(); ++i) out.base_ci95.push_back(fitted[i] ? cov.t95 * cov.se[i] : kNaN);
  std::size_t offset = m.base.size();
  for (std::size_t e = 0; e < m.effects.size(); ++e) {
    out.effect_ci95.push_back(effect_intervals(m, e, offset, cov, n));
    offset += m.effects[e].params.size();
  }
  out.rmse_Nm = rep.rmse;
  out.rows = rj.residuals.size();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

std::string model_file_json(const ModelFit& f, std::span<const double> omega, const std::string& input,
                            const std::string& model_source) {
  using nlohmann::ordered_json;
  const auto value = [](double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); };
  ordered_json j = detail::model_file_fields(f.knob, omega);
  ordered_json base = ordered_json::object();
  for (std::size_t i = 0; i < f.base_ci95.size() && i < model::kThesisParamCount; ++i)
    base[std::string(model::kThesisParamNames[i])] = value(f.base_ci95[i]);
  ordered_json effects = ordered_json::array();
  for (std::size_t e = 0; e < f.effect_ci95.size(); ++e) {
    ordered_json p = ordered_json::object();
    for (const auto& [name, ci] : f.effect_ci95[e]) p[name] = value(ci);
    effects.push_back({{"effect", std::string(effect_name(f.knob.effects[e].effect))}, {"params", p}});
  }
  j["ci95"] = {{"params", base}, {"effects", effects}};
  j["rmse_Nm"] = f.rmse_Nm;
  j["rows"] = f.rows;
  j["source"] = {{"command", "knoblab fit --model"}, {"input", input}, {"model", model_source}};
  return j.dump(2);
}

}  // namespace knoblab::discovery
