// The figure options fit and discrepancy share for --report: --format,
// --size, --dpi (apps/fit's plot/figure_options.hpp holds the grammar).
#pragma once

#include <vector>

#include "args.hpp"
#include "knoblab/fit/plot/figure_options.hpp"

namespace knoblab::cli {

// `options` followed by --format, --size and --dpi.
std::vector<OptionSpec> with_figure_options(std::vector<OptionSpec> options);

// The figure options given, defaults otherwise. Throws UsageError saying
// what is wrong, or that they were given without --report; with --report,
// std::runtime_error when PLplot here cannot draw a format asked for.
fit::plot::FigureOptions figure_options(const Args& args);

}  // namespace knoblab::cli
