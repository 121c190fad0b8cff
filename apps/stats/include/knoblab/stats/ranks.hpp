// Ranks with ties averaged, which the Friedman, Wilcoxon and Spearman
// statistics all start from.
#pragma once

#include <span>
#include <vector>

namespace knoblab::stats {

struct Ranking {
  std::vector<double> ranks;     // 1-based; tied values share their mean rank
  std::vector<double> tie_sizes; // size t of every group of ≥ 2 equal values
  // Σ (t³ − t) over the tie groups, the term every tie correction uses.
  double tie_term() const;
};

// Ranks of values (scipy.stats.rankdata's "average" method).
Ranking rank_average(std::span<const double> values);

}  // namespace knoblab::stats
