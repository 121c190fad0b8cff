// The discrepancy JSON (names fixed in docs/discrepancy.md), and
// the sentence that puts its base and final held-out RMS on the same rows.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::discovery {

namespace {

nlohmann::ordered_json params_json(const Params& p) {
  nlohmann::ordered_json o = nlohmann::ordered_json::object();
  for (const auto& [name, value] : p) o[name] = value;
  return o;
}

nlohmann::ordered_json findings_json(const std::vector<Finding>& findings) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const Finding& f : findings) {
    a.push_back({{"effect", std::string(effect_name(f.effect))},
                 {"confidence", f.confidence},
                 {"where", f.where},
                 {"explanation", f.explanation},
                 {"params", params_json(f.params)},
                 {"rmse_before_Nm", f.rmse_before_Nm},
                 {"rmse_after_Nm", f.rmse_after_Nm},
                 {"heldout_rmse_before_Nm", f.heldout_rmse_before_Nm},
                 {"heldout_rmse_after_Nm", f.heldout_rmse_after_Nm},
                 {"heldout_rows", f.heldout_rows},
                 {"support_rows", f.support_rows},
                 {"support_heldout_rmse_before_Nm", f.support_heldout_rmse_before_Nm},
                 {"support_heldout_rmse_after_Nm", f.support_heldout_rmse_after_Nm},
                 {"bic_before", f.bic_before},
                 {"bic_after", f.bic_after},
                 {"heldout_t", f.t_stat}});
  }
  return a;
}

}  // namespace

std::string to_json(const DiscrepancyResult& r, int indent) {
  nlohmann::ordered_json j;
  // Still SI; a linear axis's readers take rad as m and N·m as N.
  if (r.axis == fit::Axis::Linear) j["axis"] = fit::axis_name(r.axis);
  j["base"] = {{"params", params_json(r.base.params)},
               {"rmse_Nm", r.base.rmse_Nm},
               {"heldout_rmse_Nm", r.base.heldout_rmse_Nm},
               {"heldout_rows", r.base.heldout_rows},
               {"bic", r.base.bic},
               {"fit_percent", r.base.fit_percent},
               {"whiteness_p", r.base.whiteness_p},
               {"independence_p", r.base.independence_p},
               {"forward_rmse_rad", r.base.forward_rmse_rad},
               // fitted: Eq. 6 fitted here; given: a model held as given; refitted: a given model fitted here.
               {"source", !r.base_given ? "fitted" : r.base_held ? "given" : "refitted"}};
  j["findings"] = findings_json(r.findings);
  // Outside the documented names: found, but under the reporting bar (not in final).
  j["tentative_findings"] = findings_json(r.tentative);
  if (!r.tentative.empty()) j["tentative_heldout_rmse_Nm"] = r.tentative_heldout_rmse_Nm;
  j["min_reported_gain"] = r.min_reported_gain;
  j["final"] = {{"params", params_json(r.final_model.params)},
                {"rmse_Nm", r.final_model.rmse_Nm},
                {"heldout_rmse_Nm", r.final_model.heldout_rmse_Nm},
                {"heldout_rows", r.final_model.heldout_rows},
                {"same_rows", {{"heldout_rows", r.same_rows.rows},
                               {"base_heldout_rmse_Nm", r.same_rows.base_Nm},
                               {"final_heldout_rmse_Nm", r.same_rows.final_Nm}}},
                {"bic", r.final_model.bic},
                {"fit_percent", r.final_model.fit_percent},
                {"whiteness_p", r.final_model.whiteness_p},
                {"independence_p", r.final_model.independence_p},
                {"forward_rmse_rad", r.final_model.forward_rmse_rad}};
  j["candidates"] = nlohmann::ordered_json::array();
  for (const CandidateScore& c : r.candidates) {
    j["candidates"].push_back({{"round", c.round},
                               {"effect", std::string(effect_name(c.effect))},
                               {"heldout_gain", c.heldout_gain},
                               {"heldout_t", c.t_stat},
                               {"kept", c.kept}});
  }
  j["train_rows"] = r.train_rows;
  j["heldout_rows"] = r.heldout_rows;
  j["slow_speed_rad_s"] = r.slow_speed;
  j["blocks"] = r.blocks;
  j["seconds"] = r.seconds;
  return j.dump(indent);
}

std::string same_rows_sentence(const DiscrepancyResult& r) {
  const std::size_t base = r.base.heldout_rows, final = r.final_model.heldout_rows, both = r.same_rows.rows;
  if ((both == base && both == final) || !std::isfinite(r.same_rows.base_Nm)) return "";
  const fit::AxisUnits& u = fit::units(r.axis);
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "The base model describes %zu held-out rows, the final %zu (a delay moves rows into or out of the "
                "stick band, a coupling's %s leaves out a creeping knob); on the %zu both describe, held-out "
                "RMS %.4g → %s.",
                base, final, std::string(u.twist).c_str(), both, u.torque(r.same_rows.base_Nm),
                u.torque.with(r.same_rows.final_Nm, "%.4g").c_str());
  return buf;
}

}  // namespace knoblab::discovery
