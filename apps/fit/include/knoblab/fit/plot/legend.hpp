// A panel's legend: one entry per label of a series that is drawn.
#pragma once

#include <string>
#include <vector>

#include "knoblab/fit/plot/figure.hpp"

namespace knoblab::fit::plot {

struct LegendEntry {
  std::string label;
  Mark mark = Mark::Dots;
  Rgb color;
  double size_mm = 0.0;
};

// The labelled series that put something on the panel (a point with finite
// x and y; for vertical lines, a finite x), by legend_rank and then drawing
// order; a label shared by several series (a band's two edges) listed once,
// as its first series looks.
std::vector<LegendEntry> legend_entries(const Panel& panel);

}  // namespace knoblab::fit::plot
