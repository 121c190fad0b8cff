// The pointing study's report (thesis §4.6.2, Study 3), from its tidy table
// (tidy.hpp): Fitts' law per rendering, the movement-time ANOVA over
// renderings, the rating tests and the correlations of Tables 21–25
// (docs/studies.md, "Analysis: the pointing study's report", has every
// definition and formula). Practice rows are left out of all of it.
//
// Units are the tidy table's (degrees, seconds, bits), as the JSON keys say.
//
//   per rendering, per amplitude × width cell: n, mean movement time, the
//     end points' SD, We = 4.133·SD, IDe = log2(A/We + 1), throughput =
//     IDe / mean MT (ISO 9241-9), Welford's ID (Eq. 18, base 10, nominal W;
//     Table 27); per rendering We, IDe and throughput as the mean over its
//     cells (ISO 9241-9's "mean of means"), the Fitts line MT = a + b·IDe
//     through its cells, mean MT, mean rating, and the participants' means
//     with 95 % intervals
//   movement time: one-way repeated-measures ANOVA over renderings on each
//     participant's mean MT per rendering, Greenhouse–Geisser and Huynh–Feldt
//   rating: each participant's median rating per rendering → Friedman;
//     Wilcoxon signed-rank of each rendering against the first (the control),
//     Bonferroni-adjusted
//   Spearman over trials: movement time with rating (Table 21); rating with
//     EMG and with SC when biometrics were recorded (Table 23)
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/stats/correlation.hpp"
#include "knoblab/stats/fitts.hpp"
#include "knoblab/stats/rm_anova.hpp"
#include "knoblab/study/level_tests.hpp"
#include "knoblab/study/tidy.hpp"

namespace knoblab::study {

// One amplitude × width condition of one rendering, over every participant's
// acquisitions in it.
struct PointingCell {
  double amplitude_deg = 0, width_deg = 0;  // nominal A and W
  std::size_t n = 0;                        // acquisitions (end points)
  double movement_time_s = 0;               // mean
  double endpoint_mean_deg = 0;             // mean end point (+ past the centre)
  double endpoint_sd_deg = 0;               // SD, n − 1
  double We_deg = 0;                        // 4.133·SD
  double IDe_bits = 0;                      // log2(A/We + 1)
  double throughput_bits_per_s = 0;         // IDe / mean MT
  double welford_id = 0;                    // log10(A/W + 0.5), nominal W (Eq. 18, Table 27)
};

struct PointingRendering {
  std::string rendering;
  std::vector<PointingCell> cells;  // by amplitude, then width, ascending
  // Means over the cells (ISO 9241-9's "mean of means"), not over acquisitions.
  double We_deg = 0, IDe_bits = 0, throughput_bits_per_s = 0;
  double movement_time_s = 0;  // mean over its acquisitions
  double rating_mean = 0;      // mean over its trials (one rating each)
  std::size_t trials = 0, acquisitions = 0;
  // MT = a + b·IDe by least squares through the cells' (IDe, mean MT);
  // none with fewer than two distinct IDe (a note says so).
  std::optional<stats::LineFit> fitts_line;
  // Over the participants in the ANOVA: their mean MT in this rendering, and
  // their mean rating (what the plots draw with error bars).
  ParticipantMean movement_time_by_participant, rating_by_participant;
};

struct PointingCorrelations {
  // Spearman over trials (each trial's mean MT over its acquisitions); none
  // when the ratings or times do not vary (a note says so).
  std::optional<stats::CorrelationResult> movement_time_rating;
  // Over trials with biometrics (each trial's mean over its rows that have
  // a value); none when no EMG (SC) was recorded.
  std::optional<stats::CorrelationResult> rating_emg, rating_sc;
};

struct PointingReport {
  std::vector<PointingRendering> renderings;  // in level order; the first is the control
  // The participants in the ANOVA and the rating tests (every rendering
  // done), in the order the rows first name them.
  std::vector<std::string> participants;
  stats::RmAnovaResult anova_movement_time;
  std::optional<stats::FriedmanResult> friedman_rating;  // needs ≥ 3 renderings and some variation
  std::vector<RatingComparison> wilcoxon_rating;         // renderings 2 … k against the first (level = rendering)
  PointingCorrelations correlations;
  std::size_t trials = 0, acquisitions = 0;              // analysed (practice left out)
  // What was left out and why: participants missing a rendering, tests that
  // are undefined on these data.
  std::vector<std::string> notes;
};

struct PointingReportOptions {
  // The rendering levels in order, the control first (the protocol's order
  // of the rendering factor's levels). Empty: the order in which the
  // analysed rows first name them. When given, every rendering in the rows
  // must be in it and every level in it must have rows.
  std::vector<std::string> rendering_order;
};

// Throws std::invalid_argument with a sentence saying what is missing when
// the data cannot support the report: no analysed rows, fewer than 2
// renderings, a cell with fewer than 2 end points or no spread in them,
// fewer than 3 participants with every rendering (the ANOVA's Huynh–Feldt ε
// needs 3), rows of one trial that disagree, a rendering order that does not
// match the rows.
PointingReport pointing_report(std::span<const PointingRow> rows, const PointingReportOptions& options = {});

// The report as JSON (docs/studies.md lists the keys):
//   renderings: [{rendering, We_deg, IDe_bits, throughput_bits_per_s,
//                 movement_time_s, rating_mean, trials, acquisitions,
//                 movement_time_by_participant: {mean, low, high, participants},
//                 rating_by_participant: {…}, fitts_line: {intercept_s,
//                 slope_s_per_bit, r_squared} (when there is one),
//                 cells: [{amplitude_deg, width_deg, n, We_deg, IDe_bits,
//                          throughput_bits_per_s, movement_time_s, welford_id,
//                          endpoint_mean_deg, endpoint_sd_deg}]}],
//   anova_movement_time: {F, df1, df2, p, p_gg, epsilon_gg, p_hf, epsilon_hf,
//                         partial_eta_squared, participants},
//   friedman_rating: {chi_squared, df, p, participants} (when computed),
//   wilcoxon_rating: [{rendering, control, W, r_plus, z, p, p_bonferroni, n,
//                      zeros, method}] (W, r_plus, z, p, n and method absent
//                      when the test is undefined),
//   correlations: {movement_time_rating, rating_emg, rating_sc: {rho, p, n}}
//                 (each when computed),
//   participants: [codes], trials, acquisitions, notes: [sentences]
nlohmann::json to_json(const PointingReport& report);

// The report for a terminal: a Fitts table per rendering, the ANOVA table,
// the rating tests, the correlations and the notes.
std::string format_pointing_report(const PointingReport& report);

}  // namespace knoblab::study
