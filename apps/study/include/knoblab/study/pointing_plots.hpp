// The pointing report's figures (thesis Figures 59–62 for Study 3), drawn
// with apps/fit's plot module (docs/figures.md): each as PDF, SVG and PNG
// (the formats asked for) and its data as CSV beside it.
//
//   movement_time   each participant's mean movement time per rendering
//                   (grey), their mean with its 95 % t interval (the
//                   ANOVA's data; the ANOVA in the heading)
//   fitts           each amplitude × width cell's mean movement time against
//                   its IDe, per rendering, with the rendering's least-squares
//                   line through its cells
//   rating          each participant's mean rating per rendering (grey), their
//                   mean with its 95 % t interval (the Friedman test in the
//                   heading)
//
// Renderings are numbered on the x axes in the report's level order and
// named in the axis label; each has one colour (matplotlib's tab10) in every
// figure. A library of its own (knoblab_study_report) so that the protocol,
// the plan and the analysis need no PLplot.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

#include "knoblab/fit/plot/figure_files.hpp"
#include "knoblab/fit/plot/figure_options.hpp"
#include "knoblab/study/pointing_report.hpp"
#include "knoblab/study/tidy.hpp"

namespace knoblab::study {

// The figures above, as data. `rows` are the rows `report` was made from
// (the participants' means are drawn from them, in the report's rendering
// order). Throws std::invalid_argument when they do not fit the report: a
// rendering the report does not have, a participant of the report missing
// a rendering.
std::vector<fit::plot::NamedFigure> pointing_figures(const PointingReport& report, std::span<const PointingRow> rows);

// Creates `dir` if needed and writes movement_time, fitts and rating as the
// formats `figure` asks for (PDF, SVG and PNG by default) and CSV; returns
// the paths. Throws as pointing_figures does, std::invalid_argument for
// figure options outside their limits, std::runtime_error naming a path that
// cannot be written.
std::vector<std::filesystem::path> write_pointing_plots(const PointingReport& report,
                                                        std::span<const PointingRow> rows,
                                                        const std::filesystem::path& dir,
                                                        const fit::plot::FigureOptions& figure = {});

}  // namespace knoblab::study
