#include "knoblab/stats/nonparametric.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "knoblab/stats/distributions.hpp"
#include "knoblab/stats/ranks.hpp"
#include "subject_table.hpp"

namespace knoblab::stats {

FriedmanResult friedman(const std::vector<std::vector<double>>& y) {
  check_subject_table(y, 2, 3, "friedman");
  const double n = static_cast<double>(y.size()), k = static_cast<double>(y.front().size());
  std::vector<double> rank_sums(y.front().size(), 0.0);
  double ties = 0;
  for (const auto& row : y) {
    const Ranking ranking = rank_average(row);
    for (std::size_t j = 0; j < row.size(); ++j) rank_sums[j] += ranking.ranks[j];
    ties += ranking.tie_term();
  }
  FriedmanResult r;
  r.tie_correction = 1 - ties / (n * k * (k * k - 1));
  if (r.tie_correction <= 0)
    throw std::invalid_argument("friedman: every subject scored all conditions the same");
  double sum_squares = 0;
  for (const double s : rank_sums) sum_squares += s * s;
  r.statistic = (12 / (n * k * (k + 1)) * sum_squares - 3 * n * (k + 1)) / r.tie_correction;
  r.df = k - 1;
  r.p = chi2_sf(r.statistic, r.df);
  return r;
}

namespace {

// Two-sided p of R+ under the sign-flip null: each rank enters R+ with
// probability ½. Ranks are whole or half (ties average), so sums of doubled
// ranks are integers and the null distribution is a table over them, built
// one rank at a time; p = 2·min(P(R+ ≤ obs), P(R+ ≥ obs)), capped at 1, as
// scipy computes its exact and permutation p-values.
double exact_p(const std::vector<double>& ranks, double r_plus) {
  const auto doubled = [](double v) { return static_cast<std::size_t>(std::lround(2 * v)); };
  std::size_t total = 0;
  for (const double r : ranks) total += doubled(r);
  // probability[s]: P(2·R+ = s) over the ranks added so far.
  std::vector<double> probability(total + 1, 0.0);
  probability[0] = 1;
  std::size_t reach = 0;
  for (const double rank : ranks) {
    const std::size_t r = doubled(rank);
    reach += r;
    // The new rank's sign is + (the sum grows by r) or − (it stays), each ½.
    // Downwards, so probability[s − r] is still the old value (r ≥ 2).
    for (std::size_t s = reach; s >= r; --s)
      probability[s] = 0.5 * (probability[s] + probability[s - r]);
    for (std::size_t s = 0; s < r; ++s) probability[s] *= 0.5;
  }
  const std::size_t observed = doubled(r_plus);
  double below = 0, above = 0;
  for (std::size_t s = 0; s <= total; ++s) {
    if (s <= observed) below += probability[s];
    if (s >= observed) above += probability[s];
  }
  return std::min(1.0, 2 * std::min(below, above));
}

}  // namespace

WilcoxonResult wilcoxon(std::span<const double> x, std::span<const double> y,
                        const WilcoxonOptions& options) {
  if (x.size() != y.size())
    throw std::invalid_argument("wilcoxon: x and y must be paired (same length)");
  WilcoxonResult r;
  std::vector<double> d, magnitude;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
      throw std::invalid_argument("wilcoxon: non-finite value in pair " + std::to_string(i));
    const double di = x[i] - y[i];
    if (di == 0) {
      ++r.zeros;
      continue;
    }
    d.push_back(di);
    magnitude.push_back(std::abs(di));
  }
  if (d.empty()) throw std::invalid_argument("wilcoxon: every difference is zero");

  const Ranking ranking = rank_average(magnitude);
  r.n = d.size();
  r.ties = !ranking.tie_sizes.empty();
  for (std::size_t i = 0; i < d.size(); ++i) (d[i] > 0 ? r.r_plus : r.r_minus) += ranking.ranks[i];
  r.statistic = std::min(r.r_plus, r.r_minus);

  const double n = static_cast<double>(r.n);
  const double mean = n * (n + 1) / 4;
  const double sd = std::sqrt((n * (n + 1) * (2 * n + 1) - ranking.tie_term() / 2) / 24);
  r.z = (r.r_plus - mean) / sd;
  if (options.continuity_correction && r.z != 0) r.z -= std::copysign(0.5 / sd, r.z);

  // scipy's "auto" decides on the pair count before zeros are dropped.
  const std::size_t pairs = x.size();
  r.method = options.method;
  if (r.method == WilcoxonMethod::automatic) {
    const bool untied = !r.ties && r.zeros == 0;
    r.method = pairs <= 50 && (untied || pairs <= 13) ? WilcoxonMethod::exact : WilcoxonMethod::normal;
  }
  r.p = r.method == WilcoxonMethod::exact ? exact_p(ranking.ranks, r.r_plus)
                                          : 2 * normal_sf(std::abs(r.z));
  return r;
}

}  // namespace knoblab::stats
