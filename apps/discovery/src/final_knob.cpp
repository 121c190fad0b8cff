// The final model's terms under the effect table's names (those discrepancy
// reports and simulate --effects takes), and the model
// file that carries them (docs/discrepancy.md, "Model file").
#include "final_knob.hpp"

#include <cmath>
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

// One effect's parameters as discrepancy reports them (the effect table's
// names), without the values derived beside them: the parameters
// `knoblab simulate --effects` and a model file take (as
// model::effect_from_params reads them: no alternatives beside the
// parameters they replace).
Params settable_params(const ActiveEffect& e, const ExtendedModel& m) {
  const model::EffectRow& row = model::effect_row(e.id);
  Params out;
  for (auto& [name, value] : report_params(e, m)) {
    const model::EffectParam* p = row.param(name);
    if (p && p->settable() && p->role != model::Role::Alternative) out.emplace_back(name, value);
  }
  return out;
}

// a3_Nm, b3_Nm: a detent harmonic of odd order.
bool odd_harmonic(const std::string& name) {
  return name.size() > 1 && (name[0] == 'a' || name[0] == 'b') && name[1] >= '0' && name[1] <= '9' &&
         (name[1] - '0') % 2 == 1;
}

}  // namespace

FinalKnob final_knob_of(const ExtendedModel& m, const std::optional<fit::StickBand>& stick) {
  FinalKnob k;
  k.params = m.base;
  k.detents = m.base_fitted.size() > model::kA_pos && m.base_fitted[model::kA_pos];
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
