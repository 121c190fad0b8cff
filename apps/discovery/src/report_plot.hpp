// A small PLplot page drawer for the discrepancy report: a grid of panels
// (point clouds, stems, lines, shaded bands) or a page of text and a table.
// Internal to knoblab_discovery_report. (apps/fit/src/report.cpp has a
// richer one, private to that file; the two share only the lock and escape.)
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace knoblab::discovery::plot {

// cmap0 entries.
enum Color : int { kWhite, kBlack, kTrain, kHeld, kBand, kAdded, kColorCount };

enum class Mark { Dots, Line, Dashed, Stems, Fill };

struct Layer {
  std::string label;  // empty: not in the legend
  Mark mark = Mark::Dots;
  int color = kBlack;
  double size = 1.0;  // dot diameter or line width, in pen widths
  std::vector<double> x, y;
  std::vector<double> y_low;  // Fill: the area between y_low and y
};

struct Panel {
  std::string heading, xlabel, ylabel;
  std::vector<Layer> layers;  // drawn in this order
  double y_lo = 0.0, y_hi = 0.0;  // y_lo < y_hi: fixed y range
};

struct Page {
  std::string title, subtitle;
  std::size_t columns = 1;
  std::vector<Panel> panels;  // row-major
  bool legends = false;  // labelled layers listed right of the last column
  // A text page instead: a table (first row the header, its cells may hold
  // '\n'; first column left aligned, the others right aligned), then
  // paragraphs and, smaller, notes, wrapped to the width.
  std::vector<std::vector<std::string>> table;
  std::vector<std::string> paragraphs, notes;
};

// Writes `page` as PNG (pngcairo) or SVG (svgcairo). Throws
// std::runtime_error naming `file` when it cannot be written. Callers hold
// fit::plplot_mutex() (knoblab/fit/plplot_shared.hpp), the lock the fit
// report takes too: PLplot keeps global state.
void render(const Page& page, const std::filesystem::path& file, bool svg, int width_px,
            int height_px);

}  // namespace knoblab::discovery::plot
