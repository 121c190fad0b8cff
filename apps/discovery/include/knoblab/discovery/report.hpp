// The discrepancy report: what discover() found, as figures a person opens.
//
//   residual_position.png / .svg  residual of the base model (top) and of the
//                                 final model (bottom) against θ, on the same
//                                 y scale; held-out rows in colour, and on
//                                 the top panel what the findings added
//   residual_velocity.png / .svg  the same against ω
//   residual_time.png / .svg      the same against t
//   whiteness.png / .svg          autocorrelation of the residual (before,
//                                 after) and its cross-correlation with ω,
//                                 each with its 99 % band (whiteness.hpp)
//   summary.png / .svg            base, after each finding and final: RMS,
//                                 held-out RMS, fit %, BIC, whiteness p,
//                                 independence p; one sentence per finding
//   summary.md                    the same table and sentences as text
// Axes in presentation units (mN·m, rad, rad/s, s).
#pragma once

#include <filesystem>
#include <vector>

#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/report.hpp"

namespace knoblab::discovery {

// The fit report's options: title (shown on every page), image size in px,
// max_points (residual clouds thinned evenly to this).
using ReportOptions = fit::ReportOptions;

// Creates `dir` if needed and writes the files above; returns their paths.
// `data` is the recording discover() analysed (its sample rate and length go
// in the notes). Throws std::runtime_error naming the path when the
// directory or a file cannot be written; std::invalid_argument when the
// result's trace is empty or its columns differ in length, max_points is 0
// or the image is outside 200…16384 px a side.
// PLplot is not thread-safe: calls are serialized by a mutex of this
// library's own, so this must not run beside fit::write_report in another
// thread.
std::vector<std::filesystem::path> write_discrepancy_report(const std::filesystem::path& dir,
                                                            const fit::FitData& data,
                                                            const DiscrepancyResult& r,
                                                            const ReportOptions& opt = {});

}  // namespace knoblab::discovery
