// A figure as data: what to draw, whatever the file format. The fit and the
// discrepancy reports build these; write_figure (figure_files.hpp) draws them
// as PDF, SVG and PNG and writes their data as CSV beside them.
//
// x and y are in presentation units (mN·m, degrees, s), the units the axis
// labels name; marker sizes and line widths are in mm on the printed figure.
// Text may use PLplot's escapes #d … #u (subscript) and #u … #d
// (superscript); a literal '#' is written '##' (plot::escape, text.hpp).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace knoblab::fit::plot {

struct Rgb {
  int r = 0, g = 0, b = 0;
  double alpha = 1.0;
};

// Raw data light grey under the model in black; the blues, orange and red
// are matplotlib's "tab10" colours, so a redrawn figure can match.
namespace palette {
inline constexpr Rgb kBlack{0, 0, 0};
inline constexpr Rgb kRaw{190, 190, 190};
inline constexpr Rgb kGrey{110, 110, 110};
inline constexpr Rgb kBlue{31, 119, 180};
inline constexpr Rgb kRed{214, 39, 40};
inline constexpr Rgb kOrange{255, 127, 14};
inline constexpr Rgb kBandDark{60, 100, 190};
inline constexpr Rgb kBandLight{200, 218, 242};
}  // namespace palette

enum class Mark {
  Dots,    // a filled dot per point
  Line,    // a polyline, broken where a value is not finite
  Dashed,
  Dotted,
  Fill,    // the area between y_low and y, broken where a value is not finite
  Stems,   // a line from y = 0 to each point, and a dot on it
  VLines,  // a dashed vertical line across the panel at each x (y unused)
};

struct Series {
  std::string name;   // the CSV's `series` column: lower_snake_case, unique in its panel
  std::string label;  // legend text; empty: not in the legend
  Mark mark = Mark::Dots;
  Rgb color;
  double size_mm = 0.4;  // dot diameter or line width
  int legend_rank = 0;   // legend order; ties keep the drawing order
  std::vector<double> x, y;
  std::vector<double> y_low;  // Fill: the lower edge (y is the upper)
};

struct Panel {
  std::string name;  // the CSV's `panel` column: lower_snake_case
  std::string heading, xlabel, ylabel;
  std::vector<Series> series;  // drawn in this order: raw data first
  // A fixed y range when y_lo < y_hi (what lies beyond is cut off; say so in
  // the heading); otherwise the data's, padded, from zero when y_from_zero
  // and no value is negative.
  double y_lo = 0.0, y_hi = 0.0;
  bool y_from_zero = false;
};

// A page of text instead of panels: a table (first row the header, whose
// cells may hold '\n' for a second line; the first column left aligned, the
// others right aligned), then paragraphs and, smaller, notes.
struct TextPage {
  std::vector<std::vector<std::string>> table;
  std::vector<std::string> paragraphs, notes;
};

struct Figure {
  std::string title, subtitle;  // wrapped or shrunk to the page width
  std::size_t columns = 1;
  std::vector<Panel> panels;  // row-major; legends beside the last column
  TextPage text;              // drawn when there are no panels
  // The CSV's column names, with units, shared by every panel (e.g.
  // "position_deg", "torque_mNm", "torque_lower_mNm").
  std::string x_column = "x", y_column = "y", y_low_column = "y_low";
};

}  // namespace knoblab::fit::plot
