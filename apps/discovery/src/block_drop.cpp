#include "knoblab/discovery/block_drop.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace knoblab::discovery {

double mean_t(std::span<const double> drops) {
  const std::size_t B = drops.size();
  if (B < 2) return 0.0;
  const double mean = std::accumulate(drops.begin(), drops.end(), 0.0) / static_cast<double>(B);
  double var = 0.0;
  for (const double x : drops) var += (x - mean) * (x - mean);
  var /= static_cast<double>(B - 1);
  if (var <= 0.0) return mean > 0 ? 1e9 : 0.0;
  return mean / std::sqrt(var / static_cast<double>(B));
}

double signed_rank_z(std::span<const double> drops) {
  std::vector<double> d;
  for (const double x : drops)
    if (x != 0.0) d.push_back(x);
  const std::size_t n = d.size();
  if (n < 2) return 0.0;
  std::sort(d.begin(), d.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  double w_plus = 0.0, ties = 0.0;  // ties: Σ (t³ − t) over groups of tied |drops|
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j + 1 < n && std::abs(d[j + 1]) == std::abs(d[i])) ++j;
    const double rank = 0.5 * static_cast<double>(i + j) + 1.0, tied = static_cast<double>(j - i + 1);
    for (std::size_t k = i; k <= j; ++k)
      if (d[k] > 0.0) w_plus += rank;
    ties += tied * tied * tied - tied;
    i = j + 1;
  }
  const double N = static_cast<double>(n);
  const double var = N * (N + 1.0) * (2.0 * N + 1.0) / 24.0 - ties / 48.0;
  return var > 0.0 ? (w_plus - N * (N + 1.0) / 4.0) / std::sqrt(var) : 0.0;
}

double drop_consistency(std::span<const double> drops) {
  return std::max(mean_t(drops), signed_rank_z(drops));
}

}  // namespace knoblab::discovery
