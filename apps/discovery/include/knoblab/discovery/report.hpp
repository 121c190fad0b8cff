// The discrepancy report: what discover() found, as figures (PDF, SVG, PNG,
// each with its data as CSV; apps/fit's plot module draws them).
//
//   residual_position  residual of the base model (top) and of the final
//                      model (bottom) against θ, each on its own y scale;
//                      held-out rows in blue, and on the top panel what the
//                      findings added
//   residual_velocity  the same against ω
//   residual_time      the same against t
//   whiteness          autocorrelation of the residual (before, after) and
//                      its cross-correlation with ω, each with its 99 % band
//                      (whiteness.hpp)
//   summary            base, after each finding and final: RMS, held-out
//                      RMS, fit %, BIC, whiteness p, independence p; one
//                      sentence per finding (its CSV: the table)
//   summary.md         the same table and sentences as text
// Axes in presentation units: mN·m, degrees, deg/s, s; on a linear axis
// (DiscrepancyResult::axis) N, mm, mm/s, s (fit/axis_units.hpp).
#pragma once

#include <filesystem>
#include <vector>

#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/plot/figure_files.hpp"
#include "knoblab/fit/report.hpp"

namespace knoblab::discovery {

// The fit report's options: title (shown on every figure), formats, printed
// size and dpi, max_points (residual clouds thinned evenly to this).
using ReportOptions = fit::ReportOptions;

// The figures above, as data. `data` is the recording discover() analysed
// (its sample rate and length go in the notes). Throws
// std::invalid_argument when the result's trace is empty or its columns
// differ in length, or max_points is 0.
std::vector<fit::plot::NamedFigure> discrepancy_figures(const fit::FitData& data, const DiscrepancyResult& r,
                                                        const ReportOptions& opt = {});

// Creates `dir` if needed and writes the figures' files and summary.md;
// returns their paths. Throws as discrepancy_figures does,
// std::invalid_argument for figure options outside their limits (before
// anything is written), std::runtime_error naming the path when the
// directory or a file cannot be written.
std::vector<std::filesystem::path> write_discrepancy_report(const std::filesystem::path& dir,
                                                            const fit::FitData& data,
                                                            const DiscrepancyResult& r,
                                                            const ReportOptions& opt = {});

}  // namespace knoblab::discovery
