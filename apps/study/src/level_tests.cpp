#include "knoblab/study/level_tests.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <stdexcept>

#include "knoblab/stats/distributions.hpp"

namespace knoblab::study {

namespace {

// t₀.₉₇₅ on df degrees of freedom: the upper tail is bisected (it falls
// monotonically), to the last bit.
double t_quantile_975(double df) {
  double lo = 0, hi = 1;
  while (stats::t_sf(hi, df) > 0.025) hi *= 2;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = (lo + hi) / 2;
    (stats::t_sf(mid, df) > 0.025 ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

}  // namespace

double mean(std::span<const double> v) {
  double s = 0;
  for (const double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

ParticipantMean mean_interval(std::span<const double> v) {
  if (v.size() < 2)
    throw std::invalid_argument("a 95 % interval over participants needs at least 2 of them, not " +
                                std::to_string(v.size()));
  ParticipantMean m;
  m.participants = v.size();
  m.mean = mean(v);
  double ss = 0;
  for (const double x : v) ss += (x - m.mean) * (x - m.mean);
  const double n = static_cast<double>(v.size());
  const double half = t_quantile_975(n - 1) * std::sqrt(ss / (n - 1)) / std::sqrt(n);
  m.low = m.mean - half;
  m.high = m.mean + half;
  return m;
}

RatingTests rating_tests(const std::vector<std::vector<double>>& medians, std::span<const std::string> levels,
                         const std::string& word, std::vector<std::string>& notes) {
  RatingTests out;
  const std::size_t k = levels.size();
  if (k < 3) {
    notes.push_back("no Friedman test: it needs at least 3 " + word + "s (the Wilcoxon test compares 2)");
  } else {
    try {
      out.friedman = stats::friedman(medians);
    } catch (const std::invalid_argument&) {
      notes.push_back("no Friedman test: every participant's median rating is the same in every " + word);
    }
  }
  const double comparisons = static_cast<double>(k - 1);
  for (std::size_t j = 1; j < k; ++j) {
    RatingComparison c;
    c.level = levels[j];
    c.control = levels[0];
    std::vector<double> x, y;
    for (const auto& row : medians) {
      x.push_back(row[j]);
      y.push_back(row[0]);
    }
    try {
      c.test = stats::wilcoxon(x, y);
      c.p_bonferroni = std::min(1.0, c.test->p * comparisons);
    } catch (const std::invalid_argument&) {
      notes.push_back("no Wilcoxon test of \"" + c.level + "\" against \"" + c.control +
                      "\": every participant's median rating is the same in both");
    }
    out.wilcoxon.push_back(std::move(c));
  }
  return out;
}

std::optional<stats::CorrelationResult> spearman_or_note(std::span<const double> a, std::span<const double> b,
                                                         const std::string& what, std::vector<std::string>& notes) {
  try {
    return stats::spearman(a, b);
  } catch (const std::invalid_argument& e) {
    notes.push_back("no Spearman correlation of " + what + " over " + std::to_string(a.size()) + " trials: " + e.what());
    return std::nullopt;
  }
}

nlohmann::json to_json(const ParticipantMean& m) {
  return {{"mean", m.mean}, {"low", m.low}, {"high", m.high}, {"participants", m.participants}};
}

nlohmann::json to_json(const stats::CorrelationResult& c) { return {{"rho", c.r}, {"p", c.p}, {"n", c.n}}; }

nlohmann::json to_json(const RatingComparison& c, std::size_t participants) {
  nlohmann::json j = nlohmann::json::object();
  if (!c.test) {
    j["zeros"] = participants;
    return j;
  }
  j["W"] = c.test->statistic;
  j["r_plus"] = c.test->r_plus;
  j["z"] = c.test->z;
  j["p"] = c.test->p;
  j["p_bonferroni"] = c.p_bonferroni;
  j["n"] = c.test->n;
  j["zeros"] = c.test->zeros;
  j["method"] = c.test->method == stats::WilcoxonMethod::normal ? "normal" : "exact";
  return j;
}

std::string p_text(double p) {
  if (p >= 0.001) return std::format("{:.4f}", p);
  return std::format("{:.2e}", p);
}

std::string pad(const std::string& s, std::size_t width) {
  std::size_t shown = 0;
  for (const char ch : s) shown += (static_cast<unsigned char>(ch) & 0xC0) != 0x80 ? 1 : 0;
  return shown >= width ? s : s + std::string(width - shown, ' ');
}

std::string format_rating_tests(const RatingTests& t, std::size_t participants) {
  std::string s;
  if (t.friedman)
    s += std::format("  Friedman χ²({}, N = {}) = {:.3f}, p = {}\n", t.friedman->df, participants, t.friedman->statistic,
                     p_text(t.friedman->p));
  if (t.wilcoxon.empty()) return s;
  s += std::format("  Wilcoxon signed-rank against {}, Bonferroni over {}:\n", t.wilcoxon.front().control,
                   t.wilcoxon.size());
  for (const RatingComparison& c : t.wilcoxon) {
    if (!c.test) {
      s += std::format("    {} (no differences)\n", pad(c.level, 16));
      continue;
    }
    s += std::format("    {} W = {:>6} z = {:>7.3f}  p = {:>9}  p (Bonferroni) = {:>9}  n = {}{}, {}\n", pad(c.level, 16),
                     std::format("{}", c.test->statistic), c.test->z, p_text(c.test->p), p_text(c.p_bonferroni),
                     c.test->n, c.test->zeros ? std::format(" ({} zero)", c.test->zeros) : "",
                     c.test->method == stats::WilcoxonMethod::exact ? "exact" : "normal approximation");
  }
  return s;
}

}  // namespace knoblab::study
