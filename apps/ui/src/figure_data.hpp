// A report figure's data as the CLI stores it beside each figure
// (docs/figures.md, "CSV: the data of every figure"): long format, one row
// per plotted point, `panel,series,X,Y[,Y_lower]`. The UI draws it
// interactively (FigureView), so its plots are the report's, not a second
// rendering of the model. Qt-free, tested on its own.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace knoblab::ui {

struct FigureSeries {
  enum class Kind { Points, Line, Band };
  std::string panel, name;
  Kind kind = Kind::Points;
  std::vector<double> x, y, y_low;  // y_low: a band's lower edge
};

struct FigureData {
  std::string x_column, y_column;  // e.g. position_deg, torque_mNm
  std::vector<std::string> panels;  // in the order they first appear
  std::vector<FigureSeries> series;  // in the order they first appear
};

// Throws std::invalid_argument naming the line when the text is not such a
// CSV. How a series is drawn is read from it: a lower edge makes a band;
// raw data (`raw_…`) and anything not ordered along x are points; the rest
// are lines through their vertices.
FigureData parse_figure_csv(std::string_view csv);

// "position_deg" → "position (°)", "torque_mNm" → "torque (mN·m)".
std::string axis_label(std::string_view column);

}  // namespace knoblab::ui
