// One-way repeated-measures ANOVA: every subject scored under every
// condition (complete cases), with the sphericity corrections the thesis'
// studies report (§4.4–4.6 use Huynh–Feldt).
#pragma once

#include <cstddef>
#include <vector>

namespace knoblab::stats {

struct RmAnovaResult {
  std::size_t subjects = 0, conditions = 0;  // n, k
  double ss_conditions = 0, ss_subjects = 0, ss_error = 0;
  double df1 = 0, df2 = 0;  // k − 1, (n − 1)(k − 1)
  double f = 0, p = 0;
  // SS_conditions / (SS_conditions + SS_error): the η² the thesis prints.
  double partial_eta_squared = 0;
  // Greenhouse–Geisser ε ∈ [1/(k − 1), 1]; p_gg is p on ε·df1, ε·df2.
  double epsilon_gg = 1, p_gg = 0;
  // Huynh–Feldt ε as R's anova.mlm reports it (it may exceed 1); p_hf uses
  // min(1, ε_HF), as R does.
  double epsilon_hf = 1, p_hf = 0;
};

// y[i][j]: subject i under condition j. Needs n ≥ 3 subjects (the
// Huynh–Feldt ε is undefined for 2) and k ≥ 2 conditions, all rows the
// same length and finite, and some within-subject error variance. Throws
// std::invalid_argument otherwise.
RmAnovaResult rm_anova(const std::vector<std::vector<double>>& y);

}  // namespace knoblab::stats
