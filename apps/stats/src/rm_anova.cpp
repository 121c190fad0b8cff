#include "knoblab/stats/rm_anova.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "knoblab/stats/distributions.hpp"
#include "subject_table.hpp"

namespace knoblab::stats {

RmAnovaResult rm_anova(const std::vector<std::vector<double>>& y) {
  check_subject_table(y, 3, 2, "rm_anova");
  const std::size_t n = y.size(), k = y.front().size();
  const double nd = static_cast<double>(n), kd = static_cast<double>(k);

  bool all_equal = true;
  std::vector<double> subject_mean(n, 0.0), condition_mean(k, 0.0);
  double grand = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < k; ++j) {
      subject_mean[i] += y[i][j];
      condition_mean[j] += y[i][j];
      grand += y[i][j];
      all_equal = all_equal && y[i][j] == y[0][0];
    }
  if (all_equal) throw std::invalid_argument("rm_anova: all scores are equal");
  for (double& m : subject_mean) m /= kd;
  for (double& m : condition_mean) m /= nd;
  grand /= nd * kd;

  RmAnovaResult r;
  r.subjects = n;
  r.conditions = k;
  for (const double m : condition_mean) r.ss_conditions += nd * (m - grand) * (m - grand);
  for (const double m : subject_mean) r.ss_subjects += kd * (m - grand) * (m - grand);

  // The residuals e_ij = y_ij − subject mean − condition mean + grand mean,
  // summed directly rather than as SS_total − SS_cond − SS_subj, which
  // cancels badly when the error is small.
  std::vector<std::vector<double>> e(n, std::vector<double>(k));
  double largest_residual = 0, largest_deviation = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < k; ++j) {
      e[i][j] = y[i][j] - subject_mean[i] - condition_mean[j] + grand;
      r.ss_error += e[i][j] * e[i][j];
      largest_residual = std::max(largest_residual, std::abs(e[i][j]));
      largest_deviation = std::max(largest_deviation, std::abs(y[i][j] - grand));
    }
  // Residuals at rounding level: every subject's scores are the condition
  // effects plus an offset, so F would be ∞ (or noise over noise).
  if (largest_residual <= 1e-12 * largest_deviation)
    throw std::invalid_argument(
        "rm_anova: no within-subject error variance (each subject's scores differ from the "
        "condition means by a constant), F is undefined");

  r.df1 = kd - 1;
  r.df2 = (nd - 1) * (kd - 1);
  r.f = (r.ss_conditions / r.df1) / (r.ss_error / r.df2);
  r.p = f_sf(r.f, r.df1, r.df2);
  r.partial_eta_squared = r.ss_conditions / (r.ss_conditions + r.ss_error);

  // Greenhouse–Geisser: ε = tr(S)² / ((k − 1)·tr(S²)) with S the
  // double-centred covariance of the conditions, which is eᵀe/(n − 1); the
  // (n − 1) cancels, and tr(eᵀe) = SS_error.
  double sum_squares_of_cross_products = 0;
  for (std::size_t j = 0; j < k; ++j)
    for (std::size_t l = 0; l < k; ++l) {
      double cross = 0;
      for (std::size_t i = 0; i < n; ++i) cross += e[i][j] * e[i][l];
      sum_squares_of_cross_products += cross * cross;
    }
  r.epsilon_gg = r.ss_error * r.ss_error / (r.df1 * sum_squares_of_cross_products);
  r.p_gg = f_sf(r.f, r.epsilon_gg * r.df1, r.epsilon_gg * r.df2);

  // Huynh–Feldt (1976), as R's stats:::sphericity writes it. For n ≥ 3 the
  // numerator is > 0 ((k − 1)·ε ≥ 1) and so is the denominator, unless the
  // sample is exactly spherical with n = k: then ε_HF is +∞, which the cap
  // below makes 1.
  const double hf_denominator = r.df1 * (nd - 1 - r.df1 * r.epsilon_gg);
  r.epsilon_hf = hf_denominator > 0 ? (nd * r.df1 * r.epsilon_gg - 2) / hf_denominator
                                    : std::numeric_limits<double>::infinity();
  const double hf = std::min(1.0, r.epsilon_hf);
  r.p_hf = f_sf(r.f, hf * r.df1, hf * r.df2);
  return r;
}

}  // namespace knoblab::stats
