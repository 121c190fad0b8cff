// A figure as files: DIR/STEM.pdf, .svg, .png (the formats asked for) and
// DIR/STEM.csv, its data (figure_csv.hpp). This is how the fit and the
// discrepancy reports draw.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "knoblab/fit/plot/figure.hpp"
#include "knoblab/fit/plot/figure_options.hpp"

namespace knoblab::fit::plot {

// Writes each file whole or not at all (a temporary file renamed), and
// returns their paths, the formats first in the order asked for, the CSV
// last. `dir` must exist. Throws std::invalid_argument for options outside
// their limits (figure_options.hpp), std::runtime_error naming the file that
// cannot be written. PLplot is not thread-safe: calls from several threads
// are serialized by a mutex of the plot module's own.
std::vector<std::filesystem::path> write_figure(const Figure& fig, const std::filesystem::path& dir,
                                                const std::string& stem, const FigureOptions& opt);

// Throws std::runtime_error naming what is missing when this PLplot cannot
// draw one of `formats` (a build without that cairo driver): a command checks
// before its work, not after.
void require_formats(const std::vector<Format>& formats);

// A report's figures, by file stem.
struct NamedFigure {
  std::string stem;
  Figure figure;
};

// Called before each figure with how many are done and how many there are:
// progress, and the place to cancel (by throwing) between figures.
using BeforeFigure = std::function<void(std::size_t done, std::size_t total)>;

// Creates `dir` if needed (std::runtime_error naming it when it cannot) and
// writes every figure; returns all the paths.
std::vector<std::filesystem::path> write_figures(const std::vector<NamedFigure>& figures,
                                                 const std::filesystem::path& dir, const FigureOptions& opt,
                                                 const BeforeFigure& before_each = {});

}  // namespace knoblab::fit::plot
