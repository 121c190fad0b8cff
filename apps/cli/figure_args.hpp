// The figure options fit and discrepancy share for --report: --format,
// --size, --dpi (apps/fit's plot/figure_options.hpp holds the grammar).
#pragma once

#include <string>
#include <vector>

#include "args.hpp"
#include "knoblab/fit/plot/figure_options.hpp"

namespace knoblab::cli {

// `options` followed by --format, --size and --dpi, for the figures written
// to the directory option `dir_option` (--report; study report's --out).
std::vector<OptionSpec> with_figure_options(std::vector<OptionSpec> options, const std::string& dir_option = "report");

// The figure options given, defaults otherwise. Throws UsageError saying
// what is wrong, or that they were given without --report; with --report,
// std::runtime_error when PLplot here cannot draw a format asked for.
fit::plot::FigureOptions figure_options(const Args& args, const std::string& dir_option = "report");

}  // namespace knoblab::cli
