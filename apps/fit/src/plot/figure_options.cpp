#include "knoblab/fit/plot/figure_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace knoblab::fit::plot {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// A positive decimal number filling the whole of `s`, or NaN.
double positive(std::string_view s) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !(v > 0.0) || !std::isfinite(v))
    return std::nan("");
  return v;
}

}  // namespace

std::string_view extension(Format f) {
  switch (f) {
    case Format::Pdf: return "pdf";
    case Format::Svg: return "svg";
    case Format::Png: return "png";
  }
  return "";
}

std::vector<Format> parse_formats(std::string_view list) {
  std::vector<Format> out;
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    const std::string_view name = list.substr(at, comma - at);
    Format f;
    if (name == "pdf") f = Format::Pdf;
    else if (name == "svg") f = Format::Svg;
    else if (name == "png") f = Format::Png;
    else
      throw std::invalid_argument("unknown figure format '" + std::string(name) +
                                  "' (known: pdf, svg, png; a comma-separated list)");
    if (std::find(out.begin(), out.end(), f) != out.end())
      throw std::invalid_argument("figure format '" + std::string(name) + "' given twice");
    out.push_back(f);
    at = comma + 1;
  }
  return out;
}

void parse_size(std::string_view text, FigureOptions& opt) {
  const auto fail = [&] {
    throw std::invalid_argument("figure size '" + std::string(text) +
                                "': expected WIDTHxHEIGHT or WIDTH with a unit mm, cm or in, "
                                "e.g. 160x100mm, 16x10cm, 6.3x3.9in or 120mm");
  };
  double unit = 0.0;
  std::string_view numbers;
  for (const auto& [suffix, mm] : {std::pair{"mm", 1.0}, std::pair{"cm", 10.0}, std::pair{"in", 25.4}}) {
    if (text.size() > 2 && text.ends_with(suffix)) {
      unit = mm;
      numbers = text.substr(0, text.size() - 2);
    }
  }
  if (unit == 0.0) fail();
  const std::size_t x = numbers.find('x');
  const double w = positive(numbers.substr(0, x));
  const double h = x == std::string_view::npos ? 0.0 : positive(numbers.substr(x + 1));
  if (std::isnan(w) || std::isnan(h)) fail();
  opt.width_mm = w * unit;
  opt.height_mm = h * unit;
}

void validate(const FigureOptions& opt) {
  if (opt.formats.empty()) throw std::invalid_argument("no figure format chosen (pdf, svg, png)");
  const auto side = [](const char* what, double mm) {
    if (!(mm >= kMinSideMm && mm <= kMaxSideMm))
      throw std::invalid_argument(std::string("figure ") + what + " " + number(mm) + " mm is outside " +
                                  number(kMinSideMm) + "…" + number(kMaxSideMm) + " mm");
  };
  side("width", opt.width_mm);
  if (opt.height_mm != 0.0) side("height", opt.height_mm);
  if (opt.dpi < kMinDpi || opt.dpi > kMaxDpi)
    throw std::invalid_argument("figure resolution " + std::to_string(opt.dpi) + " dpi is outside " +
                                std::to_string(kMinDpi) + "…" + std::to_string(kMaxDpi));
  // The tallest figure the options allow: three rows of panels when the height is open.
  const double tallest = opt.height_mm > 0.0 ? opt.height_mm : default_height_mm(3, opt.width_mm);
  for (const double mm : {opt.width_mm, tallest}) {
    if (pixels(mm, opt.dpi) > kMaxPixels)
      throw std::invalid_argument("a " + number(mm) + " mm side at " + std::to_string(opt.dpi) +
                                  " dpi is " + std::to_string(pixels(mm, opt.dpi)) +
                                  " px, over the PNG limit of " + std::to_string(kMaxPixels) +
                                  " px: lower --dpi or --size");
  }
}

int pixels(double mm, int dpi) { return static_cast<int>(std::lround(mm / 25.4 * dpi)); }

double default_height_mm(std::size_t panel_rows, double width_mm) {
  return (55.0 + 40.0 * static_cast<double>(std::max<std::size_t>(1, panel_rows))) * width_mm / 160.0;
}

}  // namespace knoblab::fit::plot
