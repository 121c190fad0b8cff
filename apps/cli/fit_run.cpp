#include "fit_run.hpp"

#include <cmath>

#include "knoblab/fit/physical_checks.hpp"

namespace knoblab::cli {

FitRun fit_capture(const interchange::Capture& capture, const fit::PrepOptions& prep,
               const fit::FitOptions& options) {
  FitRun run;
  options.hooks.report("preparing");
  run.data = fit::prepare(capture, prep);
  options.hooks.check();
  run.result = fit::fit_knob(run.data, options);
  return run;
}

Presentation presentation(std::string_view name) {
  if (name == "M_acc") return {"mN·m/(rad/s²)", 1e3};
  if (name.starts_with("B_vel")) return {"mN·m/(rad/s)", 1e3};
  if (name.starts_with("C_vel") || name == "A_pos" || name.starts_with("D_")) return {"mN·m", 1e3};
  if (name == "dv") return {"rad/s", 1.0};
  return {"rad", 1.0};  // P_pos, S_pos
}

void print_fit(std::FILE* out, const fit::FitResult& r) {
  std::fprintf(out, "model %s, %zu samples, %d iterations, %.3f s\n",
               std::string(fit::model_name(r.model)).c_str(), r.samples, r.iterations, r.seconds);
  std::fprintf(out, "  %-10s %12s  %-27s %s\n", "parameter", "value", "95% CI", "unit");
  for (std::size_t k = 0; k < r.names.size(); ++k) {
    const Presentation p = presentation(r.names[k]);
    const std::string name(r.names[k]);
    if (!r.fitted[k]) {
      std::fprintf(out, "  %-10s %12s  %-27s %s\n", name.c_str(), "-", "(no detents)", p.unit);
      continue;
    }
    char ci[64];
    std::snprintf(ci, sizeof ci, "[%.5g, %.5g]", r.ci95[k][0] * p.scale, r.ci95[k][1] * p.scale);
    std::fprintf(out, "  %-10s %12.5g  %-27s %s\n", name.c_str(), r.params[k] * p.scale, ci, p.unit);
  }
  if (r.detents) {
    std::fprintf(out, "detents: %.2f per revolution (explains %.0f %% of the position residual, "
                 "false-alarm probability %.1e)\n",
                 1.0 / r.value("P_pos"), 100 * r.detent_power, r.detent_false_alarm);
  } else {
    std::fprintf(out, "detents: none found (best peak explains %.0f %% of the position residual, "
                 "false-alarm probability %.2g)\n",
                 100 * r.detent_power, r.detent_false_alarm);
  }
  if (r.stick) {
    std::fprintf(out, "stick band (Eq. 7): dv %.4g rad/s, D- %.4g mN·m, D+ %.4g mN·m (%zu samples)\n",
                 r.stick->dv, r.stick->D_neg * 1e3, r.stick->D_pos * 1e3, r.stick->samples);
  } else {
    std::fprintf(out, "stick band (Eq. 7): none found\n");
  }
  std::fprintf(out, "rmse %.4g mN·m, fit %.2f %%, BIC %.6g, 95%% CI of the torque %.4g mN·m\n",
               r.rmse_Nm * 1e3, r.fit_percent, r.bic, r.ci95_torque_Nm * 1e3);
  for (const std::string& w : fit::physical_warnings(r)) std::fprintf(out, "warning: %s\n", w.c_str());
}

}  // namespace knoblab::cli
