#include "knoblab/stats/ranks.hpp"

#include <algorithm>
#include <numeric>

namespace knoblab::stats {

double Ranking::tie_term() const {
  double sum = 0;
  for (const double t : tie_sizes) sum += t * t * t - t;
  return sum;
}

Ranking rank_average(std::span<const double> values) {
  const std::size_t n = values.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return values[i] < values[j]; });
  Ranking result{std::vector<double>(n), {}};
  for (std::size_t start = 0; start < n;) {
    std::size_t end = start + 1;  // one past the run of equal values
    while (end < n && values[order[end]] == values[order[start]]) ++end;
    // Positions start..end−1 hold ranks start+1..end; their mean:
    const double rank = 0.5 * static_cast<double>(start + 1 + end);
    for (std::size_t i = start; i < end; ++i) result.ranks[order[i]] = rank;
    if (end - start > 1) result.tie_sizes.push_back(static_cast<double>(end - start));
    start = end;
  }
  return result;
}

}  // namespace knoblab::stats
