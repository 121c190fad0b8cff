// Correlation with its two-sided p-value (the thesis' Tables 21 and 23–25
// are Spearman's ρ).
#pragma once

#include <cstddef>
#include <span>

namespace knoblab::stats {

struct CorrelationResult {
  double r = 0;  // Pearson's r, or Spearman's ρ
  double p = 0;  // two-sided, from t = r·√((n − 2)/(1 − r²)) on n − 2 df
  std::size_t n = 0;
};

// Both need n ≥ 3 pairs (a p-value needs n − 2 > 0 df), equal lengths,
// finite values, and neither sample constant (r would be 0/0). They throw
// std::invalid_argument otherwise. |r| = 1 gives p = 0.
CorrelationResult pearson(std::span<const double> x, std::span<const double> y);
// Pearson's r of the ranks, ties averaged; p as scipy.stats.spearmanr.
CorrelationResult spearman(std::span<const double> x, std::span<const double> y);

}  // namespace knoblab::stats
