// One of K and B's stable interval with the other held (load_tiles' check):
// a point well inside needs no eigenvalue problem of its own, one near an
// end is tested, one outside is not stable.
#pragma once

#include <algorithm>
#include <cmath>

namespace knoblab::hapticd {

struct StableRange {
  // Stable for lo ≤ x ≤ hi; empty (lo > hi) when the held value alone is
  // not stable. An end may be infinite: nothing that way is unstable.
  double lo = 1.0, hi = 0.0;

  template <typename Test>
  bool holds(double x, Test&& test) const {
    if (!(lo <= hi)) return false;
    // Relative to the finite ends: an infinite one would make the margin
    // infinite and send every point to its own test.
    const auto finite = [](double v) { return std::isfinite(v) ? std::abs(v) : 0.0; };
    const double margin = 1e-6 * std::max(1.0, finite(hi) + finite(lo));
    if (x >= lo + margin && x <= hi - margin) return true;
    if (x < lo - margin || x > hi + margin) return false;
    return test();  // at an end: test it
  }
};

}  // namespace knoblab::hapticd
