// Text on a figure: PLplot's escapes, how wide a string comes out, and
// fitting a long one (a title, a heading) to a width by shrinking it and then
// wrapping it, so nothing runs off the page.
//
// Widths are DejaVu Sans's advance widths, the face PLplot's cairo driver
// draws "sans" with where it is the only sans face installed (the sysroot,
// the images); another face differs by a few percent, which the margins take.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace knoblab::fit::plot {

inline constexpr double kPtMm = 25.4 / 72.0;    // one typographic point in mm
inline constexpr double kCapHeightEm = 0.729;   // DejaVu Sans: 'H' is 0.729 em tall
inline constexpr double kDescentEm = 0.236;     // below the baseline
inline constexpr double kScriptScale = 0.75;    // sub- and superscripts' size

// `plain` shown as written: PLplot's escape character '#' doubled.
std::string escape(std::string_view plain);

// A string with escapes cut into pieces of one level: 0 the baseline, -1 a
// subscript (#d), +1 a superscript (#u); "##" becomes '#'. Other escapes
// are kept as written.
struct Run {
  std::string text;
  int level = 0;
};
std::vector<Run> runs(std::string_view markup);

// The text without its escapes (for a CSV): the runs joined.
std::string plain(std::string_view markup);

// The width in ems (of the base size) of `markup` as drawn.
double width_em(std::string_view markup);
inline double width_mm(std::string_view markup, double size_pt) {
  return width_em(markup) * size_pt * kPtMm;
}

// `markup` broken at spaces into lines no wider than width_mm (a single word
// wider than that gets a line of its own).
std::vector<std::string> wrap(std::string_view markup, double width_mm, double size_pt);

// Text set to fit a width: at `size_pt` if it fits on one line, else at the
// largest size down to `min_pt` at which it does, else wrapped at `min_pt`
// into as few lines as fit, at most `max_lines` (then the size shrinks below
// min_pt until they do).
struct FittedText {
  std::vector<std::string> lines;
  double size_pt = 0.0;
};
FittedText fit_text(std::string_view markup, double width_mm, double size_pt, double min_pt,
                    std::size_t max_lines);

}  // namespace knoblab::fit::plot
