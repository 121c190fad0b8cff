#include "fit_run.hpp"

#include <cmath>
#include <numbers>
#include <string>

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

fit::Unit presentation(std::string_view name, fit::Axis axis) {
  const fit::AxisUnits& u = fit::units(axis);
  if (name == "M_acc") return u.inertia;
  if (name.starts_with("B_vel")) return u.damping;
  if (name.starts_with("C_vel") || name == "A_pos" || name.starts_with("D_")) return u.torque;
  if (name == "dv") return u.speed;
  if (name == "P_pos") return u.parameter_position;
  return {.scale = 1.0, .text = "rad"};  // S_pos: the detents' phase, an angle of the sine on either axis
}

void print_fit(std::FILE* out, const fit::FitResult& r) {
  std::fprintf(out, "model %s, %zu samples, %d iterations, %.3f s\n",
               std::string(fit::model_name(r.model)).c_str(), r.samples, r.iterations, r.seconds);
  std::fprintf(out, "  %-10s %12s  %-27s %s\n", "parameter", "value", "95% CI", "unit");
  const fit::AxisUnits& u = fit::units(r.axis);
  for (std::size_t k = 0; k < r.names.size(); ++k) {
    const fit::Unit p = presentation(r.names[k], r.axis);
    const std::string name(r.names[k]), unit(p.text);
    if (!r.fitted[k]) {
      std::fprintf(out, "  %-10s %12s  %-27s %s\n", name.c_str(), "-", "(no detents)", unit.c_str());
      continue;
    }
    char ci[64];
    std::snprintf(ci, sizeof ci, "[%.5g, %.5g]", r.ci95[k][0] * p.scale, r.ci95[k][1] * p.scale);
    std::fprintf(out, "  %-10s %12.5g  %-27s %s\n", name.c_str(), r.params[k] * p.scale, ci, unit.c_str());
  }
  if (r.detents) {
    // sin(θ/P + S): one detent every 2π·P.
    const std::string every = u.cycle.words_with(2 * std::numbers::pi * std::abs(r.value("P_pos")), "%.4g");
    std::fprintf(out, "detents: %s (explains %.0f %% of the position residual, "
                 "false-alarm probability %.1e)\n",
                 every.c_str(), 100 * r.detent_power, r.detent_false_alarm);
  } else {
    std::fprintf(out, "detents: none found (best peak explains %.0f %% of the position residual, "
                 "false-alarm probability %.2g)\n",
                 100 * r.detent_power, r.detent_false_alarm);
  }
  if (r.stick) {
    std::fprintf(out, "stick band (Eq. 7): dv %s, D- %s, D+ %s (%zu samples)\n", u.speed.with(r.stick->dv, "%.4g").c_str(),
                 u.torque.with(r.stick->D_neg, "%.4g").c_str(), u.torque.with(r.stick->D_pos, "%.4g").c_str(),
                 r.stick->samples);
  } else {
    std::fprintf(out, "stick band (Eq. 7): none found\n");
  }
  std::fprintf(out, "rmse %s, fit %.2f %%, BIC %.6g, 95%% CI of the %s %s\n", u.torque.with(r.rmse_Nm, "%.4g").c_str(),
               r.fit_percent, r.bic, std::string(u.effort).c_str(), u.torque.with(r.ci95_torque_Nm, "%.4g").c_str());
  for (const std::string& w : fit::physical_warnings(r)) std::fprintf(out, "warning: %s\n", w.c_str());
}

}  // namespace knoblab::cli
