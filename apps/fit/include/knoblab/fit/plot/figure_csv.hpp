// A figure's data as CSV, so it can be drawn again with matplotlib, R or a
// spreadsheet: long format, one row per plotted point,
//
//   panel,series,<x_column>,<y_column>,<y_low_column>
//
// (Figure's column names, with units). <y_low_column> is a shaded band's
// lower edge (its upper edge in <y_column>) and empty for the other series;
// a figure without a band has no such column. A vertical line's y is empty;
// so is a value that is not finite (a break in a line). A text page's CSV is its table, the header's two lines joined.
#pragma once

#include <string>

#include "knoblab/fit/plot/figure.hpp"

namespace knoblab::fit::plot {

std::string figure_csv(const Figure& fig);

}  // namespace knoblab::fit::plot
