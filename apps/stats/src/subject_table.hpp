// The check both subjects × conditions analyses (rm_anova, friedman) start
// with.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace knoblab::stats {

// Throws std::invalid_argument naming `what` unless y has ≥ min_subjects
// rows of the same length ≥ min_conditions, all finite.
inline void check_subject_table(const std::vector<std::vector<double>>& y, std::size_t min_subjects,
                                std::size_t min_conditions, const std::string& what) {
  if (y.size() < min_subjects)
    throw std::invalid_argument(what + ": needs at least " + std::to_string(min_subjects) +
                                " subjects (rows), got " + std::to_string(y.size()));
  const std::size_t k = y.front().size();
  if (k < min_conditions)
    throw std::invalid_argument(what + ": needs at least " + std::to_string(min_conditions) +
                                " conditions (columns), got " + std::to_string(k));
  for (std::size_t i = 0; i < y.size(); ++i) {
    if (y[i].size() != k)
      throw std::invalid_argument(what + ": subject " + std::to_string(i) + " has " +
                                  std::to_string(y[i].size()) + " scores, the first has " +
                                  std::to_string(k) + " (complete cases only)");
    for (const double v : y[i])
      if (!std::isfinite(v))
        throw std::invalid_argument(what + ": subject " + std::to_string(i) + " has a non-finite score");
  }
}

}  // namespace knoblab::stats
