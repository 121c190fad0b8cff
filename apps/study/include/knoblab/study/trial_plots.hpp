// The per-trial report's figures (thesis Figures 34–36, 52–55 in kind),
// drawn with apps/fit's plot module like the pointing figures: PDF, SVG and
// PNG as asked, and the data as CSV beside them.
//
//   rating_<scale>      each participant's mean rating per level (grey), their
//                       mean with its 95 % t interval (Friedman in the heading)
//   match_<parameter>   matching: each participant's mean setting over the
//                       reference knob's value per knob (grey), their mean
//                       with its interval; 1 is a perfect match
#pragma once

#include <filesystem>
#include <vector>

#include "knoblab/fit/plot/figure_files.hpp"
#include "knoblab/fit/plot/figure_options.hpp"
#include "knoblab/study/trial_report.hpp"

namespace knoblab::study {

// The figures above, as data. Throws std::invalid_argument for a report
// without levels.
std::vector<fit::plot::NamedFigure> trial_figures(const TrialReport& report);

// Creates `dir` if needed and writes the figures; returns the paths. Throws
// as trial_figures does, std::invalid_argument for figure options outside
// their limits, std::runtime_error naming a path that cannot be written.
std::vector<std::filesystem::path> write_trial_plots(const TrialReport& report, const std::filesystem::path& dir,
                                                     const fit::plot::FigureOptions& figure = {});

}  // namespace knoblab::study
