#include "knoblab/stats/correlation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "knoblab/stats/distributions.hpp"
#include "knoblab/stats/ranks.hpp"
#include "paired_sums.hpp"

namespace knoblab::stats {
namespace {

void check_pairs(std::span<const double> x, std::span<const double> y, const char* what) {
  if (x.size() != y.size())
    throw std::invalid_argument(std::string(what) + ": x and y must be paired (same length)");
  if (x.size() < 3)
    throw std::invalid_argument(std::string(what) + ": needs at least 3 pairs, got " +
                                std::to_string(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
      throw std::invalid_argument(std::string(what) + ": non-finite value in pair " + std::to_string(i));
}

CorrelationResult correlate(std::span<const double> x, std::span<const double> y, const char* what) {
  const PairedSums s = paired_sums(x, y);
  if (s.sxx == 0 || s.syy == 0)
    throw std::invalid_argument(std::string(what) + ": a sample is constant, the correlation is undefined");
  CorrelationResult c;
  c.n = x.size();
  // Rounding can push |r| a hair past 1.
  c.r = std::clamp(s.sxy / std::sqrt(s.sxx * s.syy), -1.0, 1.0);
  const double df = static_cast<double>(c.n) - 2;
  const double one_minus_r2 = (1 - c.r) * (1 + c.r);
  c.p = one_minus_r2 == 0 ? 0.0 : t_two_sided_p(c.r * std::sqrt(df / one_minus_r2), df);
  return c;
}

}  // namespace

CorrelationResult pearson(std::span<const double> x, std::span<const double> y) {
  check_pairs(x, y, "pearson");
  return correlate(x, y, "pearson");
}

CorrelationResult spearman(std::span<const double> x, std::span<const double> y) {
  check_pairs(x, y, "spearman");
  const Ranking rx = rank_average(x), ry = rank_average(y);
  return correlate(rx.ranks, ry.ranks, "spearman");
}

}  // namespace knoblab::stats
