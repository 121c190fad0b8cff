// Comparisons across the levels of one factor, the way the thesis compared
// its renderings, stimuli and textures in every study; shared by the
// pointing report and the per-trial report so both test ratings alike.
//
//   a mean over participants with its 95 % t interval
//   ratings: each participant's median per level → Friedman over the levels;
//     Wilcoxon signed-rank of each level against the first (the control),
//     Bonferroni-adjusted over the comparisons
//   a Spearman correlation, or a note saying why there is none
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/stats/correlation.hpp"
#include "knoblab/stats/nonparametric.hpp"

namespace knoblab::study {

// A mean over participants with its 95 % t interval (mean ± t₀.₉₇₅,ₙ₋₁·SD/√n).
struct ParticipantMean {
  double mean = 0, low = 0, high = 0;
  std::size_t participants = 0;
};

// One level's ratings against the control's: Wilcoxon signed-rank on the
// participants' medians (stats::wilcoxon's defaults, scipy's: zero
// differences dropped; exact for small samples, ties included).
struct RatingComparison {
  std::string level, control;
  // None when every participant's median equals the control's (a note says so).
  std::optional<stats::WilcoxonResult> test;
  double p_bonferroni = 1;  // min(1, p × the number of comparisons)
};

struct RatingTests {
  std::optional<stats::FriedmanResult> friedman;  // needs ≥ 3 levels and some variation
  std::vector<RatingComparison> wilcoxon;         // levels 2 … k against the first
};

double mean(std::span<const double> v);
double median(std::vector<double> v);

// Mean and 95 % t interval of v. Throws std::invalid_argument for fewer than
// 2 values.
ParticipantMean mean_interval(std::span<const double> v);

// medians[participant][level], every participant with every level; `levels`
// names them, the control first; `word` is what a level is in the notes
// ("rendering", "texture"). What is undefined on these data (every median
// the same) is left out with a note added to `notes`.
RatingTests rating_tests(const std::vector<std::vector<double>>& medians, std::span<const std::string> levels,
                         const std::string& word, std::vector<std::string>& notes);

// Spearman's ρ of a with b, or none with a note ("no Spearman correlation of
// WHAT over n trials: why") when it is undefined (too few, no variation).
std::optional<stats::CorrelationResult> spearman_or_note(std::span<const double> a, std::span<const double> b,
                                                         const std::string& what, std::vector<std::string>& notes);

nlohmann::json to_json(const ParticipantMean& m);              // {mean, low, high, participants}
nlohmann::json to_json(const stats::CorrelationResult& c);     // {rho, p, n}
// {W, r_plus, z, p, p_bonferroni, n, zeros, method}; without a test just
// {zeros: participants}. The caller adds the level's and control's names
// under its own keys.
nlohmann::json to_json(const RatingComparison& c, std::size_t participants);

// p with its digits, small ones in exponent form (1.23e-07), rather than
// "< .001": a reader may want the value.
std::string p_text(double p);
// s padded to `width` columns as shown (UTF-8 continuation bytes take none).
std::string pad(const std::string& s, std::size_t width);
// The rating tests for a terminal, indented by two spaces.
std::string format_rating_tests(const RatingTests& t, std::size_t participants);

}  // namespace knoblab::study
