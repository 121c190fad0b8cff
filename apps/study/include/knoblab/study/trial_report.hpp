// The report of a study analysed per trial — matching (§3.4), list
// selection (§4.5) and textures (§4.4) — over the levels of one factor (the
// knob, the stimulus, the texture), from its trials (one TrialRow each,
// practice left out; docs/studies.md, "Analysis: the per-trial report"):
//
//   per level: trials; per rating scale and per numeric measure, the mean
//     over trials and the participants' means with 95 % intervals
//   per scale: each participant's median per level → Friedman; Wilcoxon
//     signed-rank of each level against the first, Bonferroni (level_tests)
//   per scale: Spearman over trials with EMG and with SC when recorded
//     (thesis Tables 23–25: ratings against the biometrics)
//   matching: per knob and slider, the reference's value, the participants'
//     mean match with its interval and their ratio (thesis Tables 12–14)
//
// A participant's value in a level is the mean (the median, for the rating
// tests) over their trials in it, whatever the other factors' levels were.
// Units are the rows': SI for the sliders, µV and µS for the biometrics.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/study/level_tests.hpp"

namespace knoblab::study {

struct TrialRow {
  std::string participant;
  unsigned block = 0, trial = 0;
  bool practice = false;
  std::map<std::string, std::string> levels;  // factor → level
  std::map<std::string, double> ratings;      // scale → value (affect grid: affect_grid_valence, …)
  std::map<std::string, double> measures;     // numeric measures (sliders: slider_M_acc, … SI)
  std::optional<double> emg_uV, sc_uS;        // the trial's scored biometrics
};

struct TrialReportOptions {
  std::string factor;               // the factor compared; its levels in order, the first the control
  std::vector<std::string> levels;  // every one must have analysed trials
  // Matching: each knob's reference values (level → slider parameter → SI,
  // as the measure slider_<parameter>), for the comparison of Tables 12–14.
  // Empty otherwise.
  std::map<std::string, std::map<std::string, double>> references;
};

struct LevelSummary {
  std::string level;
  std::size_t trials = 0;
  std::map<std::string, double> rating_mean, measure_mean;  // over trials
  // Over the participants with every level: each one's mean (in the
  // report's participant order; what the plots draw) and their mean with
  // its interval. A name some participant has no value of here is absent.
  std::map<std::string, std::vector<double>> rating_values, measure_values;
  std::map<std::string, ParticipantMean> rating_by_participant, measure_by_participant;
};

struct ScaleTests {
  std::string scale;
  RatingTests tests;
  std::optional<stats::CorrelationResult> emg, sc;  // Spearman over trials, when recorded
};

struct MatchEstimate {
  std::string level, parameter;  // the knob; M_acc, B_vel, A_pos, detents_per_rev
  double reference = 0;          // SI, the reference knob's value
  ParticipantMean matched;       // the participants' mean setting, SI
  double ratio = 0;              // matched mean / reference (none for a zero reference: NaN, a note)
};

struct TrialReport {
  std::string factor;
  std::vector<LevelSummary> levels;
  std::vector<std::string> participants;  // with every level: the tests' cases
  std::vector<ScaleTests> scales;
  std::vector<MatchEstimate> matches;  // matching only
  std::size_t trials = 0;              // analysed
  std::vector<std::string> notes;
};

// Throws std::invalid_argument with a sentence when the rows cannot support
// the report: no analysed rows, a factor the rows lack, a level without
// trials or not in `levels`, fewer than 2 levels, fewer than 2 participants
// with every level.
TrialReport trial_report(std::span<const TrialRow> rows, const TrialReportOptions& options);

// As JSON (docs/studies.md lists the keys):
//   factor, levels: [{level, trials, rating_mean: {scale: v}, measure_mean: {…},
//                     rating_by_participant: {scale: {mean, low, high, participants}},
//                     measure_by_participant: {…}}],
//   scales: [{scale, friedman: {chi_squared, df, p, participants} (when computed),
//             wilcoxon: [{level, control, W, r_plus, z, p, p_bonferroni, n, zeros, method}],
//             emg, sc: {rho, p, n} (when computed)}],
//   matches: [{level, parameter, reference, matched: {…}, ratio}],
//   participants, trials, notes
nlohmann::json to_json(const TrialReport& report);

// For a terminal: the levels' table, the tests per scale, the matching
// comparison and the notes.
std::string format_trial_report(const TrialReport& report);

}  // namespace knoblab::study
