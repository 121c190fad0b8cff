#include "knoblab/fit/result_json.hpp"

#include <nlohmann/json.hpp>

#include "knoblab/fit/physical_checks.hpp"

namespace knoblab::fit {

std::string to_json(const FitResult& r, int indent) {
  nlohmann::ordered_json j;
  j["model"] = model_name(r.model);
  // Still SI; a linear axis's readers take rad as m and N·m as N.
  if (r.axis == Axis::Linear) j["axis"] = axis_name(r.axis);
  nlohmann::ordered_json params, ci, se, held = nlohmann::json::array();
  for (std::size_t k = 0; k < r.names.size(); ++k) {
    const std::string name(r.names[k]);
    params[name] = r.params[k];
    if (r.fitted[k]) {
      ci[name] = {r.ci95[k][0], r.ci95[k][1]};
      se[name] = r.se[k];
    } else {
      ci[name] = nullptr;
      se[name] = nullptr;
      held.push_back(name);
    }
  }
  j["params"] = params;
  j["ci95"] = ci;
  j["se"] = se;
  j["held"] = held;
  const double P = r.params[r.index("P_pos")];
  j["detents"] = {{"present", r.detents},
                  {"per_rev", r.detents ? nlohmann::ordered_json(1.0 / P) : nullptr},
                  {"power", r.detent_power},
                  {"false_alarm", r.detent_false_alarm}};
  if (r.stick) {
    j["stick"] = {{"dv", r.stick->dv}, {"D_neg", r.stick->D_neg}, {"D_pos", r.stick->D_pos},
                  {"samples", r.stick->samples}};
  } else {
    j["stick"] = nullptr;
  }
  j["rmse_Nm"] = r.rmse_Nm;
  j["fit_percent"] = r.fit_percent;
  j["bic"] = r.bic;
  j["ci95_torque_Nm"] = r.ci95_torque_Nm;
  j["covariance_inflation"] = r.covariance_inflation;
  j["samples"] = r.samples;
  j["outliers"] = r.outliers;
  j["iterations"] = r.iterations;
  j["seconds"] = r.seconds;
  j["warnings"] = physical_warnings(r);
  return j.dump(indent);
}

std::string knob_json(const FitResult& r) {
  nlohmann::ordered_json j;
  j["model"] = model_name(r.model);
  nlohmann::ordered_json params;
  for (std::size_t k = 0; k < r.names.size(); ++k) params[std::string(r.names[k])] = r.params[k];
  j["params"] = params;
  if (r.stick) j["stick"] = {{"dv", r.stick->dv}, {"D_neg", r.stick->D_neg}, {"D_pos", r.stick->D_pos}};
  return j.dump();
}

}  // namespace knoblab::fit
