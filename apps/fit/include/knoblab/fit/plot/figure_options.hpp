// Which files a figure becomes and how big: formats, printed size, PNG
// resolution; and the command-line grammar for them
// (--format pdf,svg,png --size 160x100mm --dpi 300).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace knoblab::fit::plot {

enum class Format { Pdf, Svg, Png };

// "pdf", "svg", "png": the file extension, without the dot.
std::string_view extension(Format f);

struct FigureOptions {
  std::vector<Format> formats{Format::Pdf, Format::Svg, Format::Png};
  double width_mm = 160.0;
  // 0: each figure's own height for its rows of panels (default_height_mm).
  double height_mm = 0.0;
  int dpi = 300;  // PNG only; PDF and SVG are vector
};

// Limits: 40…1000 mm a side, 50…2400 dpi, a PNG at most 16384 px a side.
inline constexpr double kMinSideMm = 40.0, kMaxSideMm = 1000.0;
inline constexpr int kMinDpi = 50, kMaxDpi = 2400, kMaxPixels = 16384;

// "pdf,svg,png": any of them, in any order, each once. Throws
// std::invalid_argument saying which part is wrong and what is known.
std::vector<Format> parse_formats(std::string_view list);

// "160x100mm", "16x10cm", "6.3x3.9in" (width × height), or a width alone
// ("120mm": each figure keeps its own proportions). Sets width_mm and
// height_mm (0 for a width alone). Throws std::invalid_argument.
void parse_size(std::string_view text, FigureOptions& opt);

// Throws std::invalid_argument when a side, the dpi or a PNG's pixel size is
// outside the limits above, or no format is chosen.
void validate(const FigureOptions& opt);

// A length printed at `dpi`, in whole pixels.
int pixels(double mm, int dpi);

// A figure's height when the options leave it open: 55 mm plus 40 mm a row
// of panels at 160 mm wide, in proportion for other widths.
double default_height_mm(std::size_t panel_rows, double width_mm);

}  // namespace knoblab::fit::plot
