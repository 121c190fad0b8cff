// Axis ticks at round numbers (1, 2, 2.5 or 5 times a power of ten) and
// their labels, written with as many decimals as the step needs and a true
// minus sign, as matplotlib labels them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace knoblab::fit::plot {

struct Ticks {
  double step = 0.0;
  std::vector<double> at;           // inside [lo, hi]
  std::vector<std::string> labels;  // one per tick
};

// About `target` ticks (never fewer than two when the range allows) over
// [lo, hi], lo < hi.
Ticks nice_ticks(double lo, double hi, std::size_t target);

// The data range [lo, hi] widened by `pad` of its span on each side; a range
// of one value (or none) gets a width of its own.
struct Range {
  double lo = 0.0, hi = 0.0;
};
Range padded(double lo, double hi, double pad);

}  // namespace knoblab::fit::plot
