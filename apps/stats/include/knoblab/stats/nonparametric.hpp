// Rank tests for ordinal ratings (the thesis' self-reports, §4.6.2): the
// Friedman test across conditions and the Wilcoxon signed-rank test between
// two. Both match scipy.stats (friedmanchisquare, wilcoxon with its
// defaults), which the tests check them against.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace knoblab::stats {

struct FriedmanResult {
  double statistic = 0;       // χ², corrected for ties within subjects
  double df = 0;              // k − 1
  double p = 0;               // χ² upper tail
  double tie_correction = 1;  // C = 1 − Σ(t³ − t)/(n·k·(k² − 1)); χ² is divided by it
};

// y[i][j]: subject i under condition j; ranks within each subject. Needs
// n ≥ 2 subjects, k ≥ 3 conditions (for two, use wilcoxon), complete finite
// rows, and at least one subject whose scores are not all equal. Throws
// std::invalid_argument otherwise.
FriedmanResult friedman(const std::vector<std::vector<double>>& y);

enum class WilcoxonMethod {
  // scipy's method="auto": exact for ≤ 50 pairs without ties or zero
  // differences; with ties or zeros exact for ≤ 13 pairs (scipy enumerates
  // all 2ⁿ sign flips there), the normal approximation otherwise.
  automatic,
  // The sign-flip distribution of the ranks as they are, ties included.
  exact,
  // Normal approximation with the tie-corrected variance.
  normal,
};

struct WilcoxonOptions {
  WilcoxonMethod method = WilcoxonMethod::automatic;
  // ±0.5 on the rank sum in the normal approximation; off, as in scipy.
  bool continuity_correction = false;
};

struct WilcoxonResult {
  double statistic = 0;         // W = min(R+, R−), as scipy reports it
  double r_plus = 0, r_minus = 0;
  double p = 0;                 // two-sided
  double z = 0;                 // (R+ − n(n+1)/4)/σ, continuity-corrected if asked
  std::size_t n = 0;            // pairs ranked (nonzero differences)
  std::size_t zeros = 0;        // pairs dropped for a zero difference
  bool ties = false;            // equal |differences| among the ranked pairs
  WilcoxonMethod method = WilcoxonMethod::exact;  // the one used: exact or normal
};

// Paired samples x[i], y[i]; differences d = x − y. Zero differences are
// dropped before ranking (Wilcoxon's method, scipy's zero_method="wilcox").
// Throws std::invalid_argument for unequal lengths, non-finite values or
// when no difference is nonzero.
WilcoxonResult wilcoxon(std::span<const double> x, std::span<const double> y,
                        const WilcoxonOptions& options = {});

}  // namespace knoblab::stats
