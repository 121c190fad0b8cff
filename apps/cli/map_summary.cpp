#include "map_summary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "knoblab/model/periodogram.hpp"

namespace knoblab::cli {

MapSummary summarize_map(const interchange::StaticMap& m, std::size_t max_harmonics) {
  interchange::validate(m);
  MapSummary s;
  s.points = m.size();
  s.theta_min = m.theta.front();
  s.theta_max = m.theta.back();
  std::vector<double> gaps;
  for (std::size_t i = 1; i < m.size(); ++i) gaps.push_back(m.theta[i] - m.theta[i - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  s.spacing = gaps[gaps.size() / 2];
  const auto [lo, hi] = std::minmax_element(m.torque.begin(), m.torque.end());
  s.torque_min = *lo;
  s.torque_max = *hi;
  double sum = 0, sq = 0;
  for (double q : m.torque) {
    sum += q;
    sq += q * q;
  }
  s.torque_mean = sum / static_cast<double>(s.points);
  s.torque_rms = std::sqrt(sq / static_cast<double>(s.points));

  // Above half the points per revolution a harmonic aliases onto a lower one.
  const double per_rev = 2 * std::numbers::pi / s.spacing;
  const double k_max = std::min(1024.0, std::floor(per_rev / 2));
  if (k_max < 1) return s;
  const auto pg = model::angular_periodogram(m.theta, m.torque, 1.0, k_max, 1.0);
  std::vector<std::size_t> order(pg.frequency.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const std::size_t n = std::min(max_harmonics, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                    [&](std::size_t a, std::size_t b) { return pg.power[a] > pg.power[b]; });
  for (std::size_t i = 0; i < n; ++i) {
    const double f = std::round(pg.frequency[order[i]]);
    const auto fit = model::fit_sinusoid(m.theta, m.torque, f);
    s.harmonics.push_back({static_cast<int>(f), fit.amplitude, fit.power});
  }
  return s;
}

}  // namespace knoblab::cli
