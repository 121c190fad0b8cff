#include "knoblab/stats/fitts.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "paired_sums.hpp"

namespace knoblab::stats {
namespace {

void require_finite(std::span<const double> v, const char* what, const char* name) {
  for (const double a : v)
    if (!std::isfinite(a)) throw std::invalid_argument(std::string(what) + ": non-finite " + name);
}

}  // namespace

double welford_index_of_difficulty(double amplitude, double width, double log_base) {
  if (!(amplitude > 0) || !(width > 0) || !std::isfinite(amplitude) || !std::isfinite(width))
    throw std::invalid_argument("welford_index_of_difficulty: amplitude and width must be finite and > 0");
  if (!(log_base > 1) || !std::isfinite(log_base))
    throw std::invalid_argument("welford_index_of_difficulty: log base must be finite and > 1");
  return std::log(amplitude / width + 0.5) / std::log(log_base);
}

EndpointSpread endpoint_spread(std::span<const double> endpoints) {
  if (endpoints.size() < 2)
    throw std::invalid_argument("endpoint_spread: needs at least 2 end-points, got " +
                                std::to_string(endpoints.size()));
  require_finite(endpoints, "endpoint_spread", "end-point");
  EndpointSpread s;
  s.n = endpoints.size();
  s.mean = mean(endpoints);
  double sum_squares = 0;
  for (const double a : endpoints) sum_squares += (a - s.mean) * (a - s.mean);
  s.variance = sum_squares / static_cast<double>(s.n - 1);
  s.sd = std::sqrt(s.variance);
  return s;
}

EffectiveThroughput effective_throughput(double amplitude, std::span<const double> endpoints,
                                         std::span<const double> movement_times) {
  if (!(amplitude > 0) || !std::isfinite(amplitude))
    throw std::invalid_argument("effective_throughput: amplitude must be finite and > 0");
  if (movement_times.empty()) throw std::invalid_argument("effective_throughput: no movement times");
  require_finite(movement_times, "effective_throughput", "movement time");
  for (const double t : movement_times)
    if (!(t > 0)) throw std::invalid_argument("effective_throughput: movement times must be > 0");
  const EndpointSpread spread = endpoint_spread(endpoints);
  if (spread.sd == 0)
    throw std::invalid_argument("effective_throughput: all end-points are equal, the effective width is 0");
  EffectiveThroughput e;
  e.effective_width = kEffectiveWidthPerSd * spread.sd;
  e.index_of_difficulty = std::log2(amplitude / e.effective_width + 1);
  e.mean_movement_time = mean(movement_times);
  e.throughput = e.index_of_difficulty / e.mean_movement_time;
  return e;
}

LineFit fit_line(std::span<const double> index_of_difficulty, std::span<const double> movement_time) {
  const auto x = index_of_difficulty;
  const auto y = movement_time;
  if (x.size() != y.size()) throw std::invalid_argument("fit_line: ID and MT must be paired (same length)");
  if (x.size() < 2) throw std::invalid_argument("fit_line: needs at least 2 points");
  require_finite(x, "fit_line", "ID");
  require_finite(y, "fit_line", "MT");
  const auto [mx, my, sxx, syy, sxy] = paired_sums(x, y);
  if (sxx == 0) throw std::invalid_argument("fit_line: every ID is the same, the slope is undefined");
  if (syy == 0) throw std::invalid_argument("fit_line: every MT is the same, r² is undefined");
  LineFit f;
  f.n = x.size();
  f.slope = sxy / sxx;
  f.intercept = my - f.slope * mx;
  f.r_squared = sxy * sxy / (sxx * syy);
  return f;
}

}  // namespace knoblab::stats
