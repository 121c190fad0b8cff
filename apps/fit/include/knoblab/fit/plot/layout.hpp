// Where everything on a figure goes, in mm on the printed page (origin at
// its bottom left): the plot boxes and their data ranges, every piece of
// text (titles, headings, axis and tick labels, legends, a text page's
// table and paragraphs), the frames and ticks, the legend samples. Text is
// measured (text.hpp), shrunk or wrapped to fit, and the boxes take what is
// left, so nothing is cut off at any page size. The drawing (render.hpp)
// follows it for every format, so a PDF, an SVG and a PNG of one figure
// look the same.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "knoblab/fit/plot/figure.hpp"
#include "knoblab/fit/plot/legend.hpp"

namespace knoblab::fit::plot {

struct Box {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

enum class Anchor { Start, Middle, End };

struct TextItem {
  std::string text;            // with escapes (text.hpp)
  double x = 0.0, y = 0.0;     // the anchor point on the baseline
  double size_pt = 0.0;
  Anchor anchor = Anchor::Start;
  bool vertical = false;       // reading upwards, turned 90° anticlockwise
};

// Where a text's glyphs can reach: its measured width along the baseline,
// from its descent below to accents above its capitals.
Box extent(const TextItem& t);

struct Segment {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  double width_mm = 0.2;
};

struct LegendSample {
  LegendEntry entry;
  Box box;  // where its line, dot or patch goes; the text is a TextItem
};

struct PanelLayout {
  Box box;                                   // the plot area
  double x_lo = 0.0, x_hi = 1.0, y_lo = 0.0, y_hi = 1.0;  // its data window
  std::vector<LegendSample> legend;
};

struct Layout {
  double width_mm = 0.0, height_mm = 0.0;
  std::vector<PanelLayout> panels;  // one per Figure::panels
  std::vector<TextItem> texts;
  std::vector<Segment> rules;  // frames, ticks, the table's rule: black
};

// `height_mm` 0: the figure's own (default_height_mm for panels; a text page
// as tall as its text).
Layout layout_figure(const Figure& fig, double width_mm, double height_mm);

}  // namespace knoblab::fit::plot
