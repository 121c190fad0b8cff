// Fit reports: the thesis' characterization figures (Figures 17–34) for one
// fit, as PDF, SVG and PNG with each figure's data as CSV beside it
// (plot/figure_files.hpp).
//
//   torque_position   top: raw τ and fitted τ against θ; middle: raw
//                     τ_pos = τ − τ_acc − τ_vel and fitted τ_pos with its
//                     95% bands; bottom: the residual τ − τ̂ with both 95%
//                     bands shaded
//   torque_velocity   the same against θ̇ (raw τ_vel = τ − τ_acc − τ_pos),
//                     the stick band's limits marked
//   torque_time       raw and fitted τ against time, and the residual with
//                     the bands shaded
//   ci_torque         95% band half-width against fitted τ (Fig. 24)
// The bands are hundredths of a mN·m beside torques of tens, so on the torque
// panels they sit inside the fitted line; the residual panels (y range six
// robust SDs or the bands' width, transients counted in the heading) are
// where they are seen.
// Axes in presentation units: mN·m, degrees, deg/s, s; for a linear axis
// (FitResult::axis) N, mm, mm/s, s, and F for τ (axis_units.hpp).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/plot/figure_files.hpp"
#include "knoblab/fit/plot/figure_options.hpp"
#include "knoblab/fit/run_hooks.hpp"

namespace knoblab::fit {

struct ReportOptions {
  std::string title;                // e.g. the knob or capture name, shown on every figure
  plot::FigureOptions figure;       // formats, printed size, PNG dpi
  std::size_t max_points = 20000;   // raw clouds are thinned evenly to this
  // Progress ("drawing the report", figure k of n) and cancellation, checked
  // before each figure: the report then throws Cancelled, its finished files
  // left in `dir` (draw into a scratch directory to keep none).
  RunHooks hooks;
};

// The figures above, as data. `p` is predict(r, data). Throws
// std::invalid_argument when `p` or the columns of `data` differ in length
// from data.size() (observation_half may be empty), when data is empty or
// max_points is 0.
std::vector<plot::NamedFigure> report_figures(const FitResult& r, const FitData& data,
                                              const Prediction& p, const ReportOptions& opt = {});

// Creates `dir` if needed and writes the figures' files; returns their
// paths. Throws as report_figures does, std::invalid_argument for figure
// options outside their limits (before anything is written) and
// std::runtime_error naming the path when the directory or a file cannot be
// written. Safe to call from several threads (PLplot calls are serialized).
std::vector<std::filesystem::path> write_report(const FitResult& r, const FitData& data,
                                                const Prediction& p,
                                                const std::filesystem::path& dir,
                                                const ReportOptions& opt = {});

}  // namespace knoblab::fit
