// The sample mean and the centred sums of squares and products of paired
// samples: what the correlations and the Fitts line are both computed from.
// Callers check sizes and finiteness first.
#pragma once

#include <cstddef>
#include <span>

namespace knoblab::stats {

inline double mean(std::span<const double> v) {
  double sum = 0;
  for (const double a : v) sum += a;
  return sum / static_cast<double>(v.size());
}

struct PairedSums {
  double mean_x = 0, mean_y = 0;
  double sxx = 0, syy = 0, sxy = 0;  // Σ(x − x̄)², Σ(y − ȳ)², Σ(x − x̄)(y − ȳ)
};

inline PairedSums paired_sums(std::span<const double> x, std::span<const double> y) {
  PairedSums s;
  s.mean_x = mean(x);
  s.mean_y = mean(y);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double dx = x[i] - s.mean_x, dy = y[i] - s.mean_y;
    s.sxx += dx * dx;
    s.syy += dy * dy;
    s.sxy += dx * dy;
  }
  return s;
}

}  // namespace knoblab::stats
