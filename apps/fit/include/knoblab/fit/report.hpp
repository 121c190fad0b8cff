// Fit reports: the thesis' characterization figures (Figures 17–34) for one
// fit, drawn with PLplot into image files a person or the UI opens.
//
//   torque_position.png / .svg   top: raw τ and fitted τ against θ with the
//                                95% band; middle: raw τ_pos = τ − τ_acc − τ_vel
//                                and fitted τ_pos with its band; bottom: the
//                                residual τ − τ̂ with both 95% bands shaded
//   torque_velocity.png / .svg   the same against θ̇ (raw τ_vel = τ − τ_acc − τ_pos)
//   torque_time.png / .svg       raw and fitted τ against time, and the residual
//                                with the bands shaded
//   ci_torque.png / .svg         95% band half-width against fitted τ (Fig. 24)
// The bands are hundredths of a mN·m beside torques of tens, so on the torque
// panels they sit inside the fitted line; the residual panels (y range six
// robust SDs or the bands' width, transients counted in the heading) are
// where they are seen.
// Axes in presentation units (mN·m, rad, rad/s, s), labelled with them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/run_hooks.hpp"

namespace knoblab::fit {

struct ReportOptions {
  std::string title;           // e.g. the knob or capture name, shown on every plot
  int width_px = 1200;
  int height_px = 900;
  std::size_t max_points = 20000;  // raw clouds are thinned evenly to this
  // Progress ("drawing the report", file k of n) and cancellation, checked
  // before each file: the report then throws Cancelled, its finished files
  // left in `dir` (draw into a scratch directory to keep none).
  RunHooks hooks;
};

// Creates `dir` if needed and writes the files above; returns their paths.
// `p` is predict(r, data). Throws std::runtime_error (naming the path) when
// the directory or a file cannot be written, std::invalid_argument when `p`
// or the columns of `data` differ in length from data.size() (observation_half
// may be empty), when data is empty, max_points is 0 or the image is outside
// 200…16384 px a side.
// PLplot is not thread-safe: calls are serialized by an internal mutex, and
// nothing else in the process may use PLplot while one runs.
std::vector<std::filesystem::path> write_report(const FitResult& r, const FitData& data,
                                                const Prediction& p,
                                                const std::filesystem::path& dir,
                                                const ReportOptions& opt = {});

}  // namespace knoblab::fit
