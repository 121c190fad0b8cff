// The per-trial report (matching, list selection, textures): ratings
// compared across the levels of one factor on each participant's median,
// measures per level, the matching comparison with the reference knobs, the
// biometric correlations, what is left out and what is refused. The figures
// are worked by hand here; the tests themselves (Friedman, Wilcoxon,
// Spearman) are the ones the pointing report checks against R.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/study/trial_report.hpp"

namespace knoblab::study {
namespace {

TrialRow row(const std::string& participant, const std::string& level, double rating, unsigned trial = 0) {
  TrialRow r;
  r.participant = participant;
  r.trial = trial;
  r.levels = {{"knob", level}, {"context", "freeform"}};
  r.ratings = {{"sam_valence", rating}};
  return r;
}

// Four participants who all rank the knobs the same way (a < b < c), two
// trials each per knob, so each one's medians are the trials' means.
std::vector<TrialRow> ranked_rows() {
  std::vector<TrialRow> rows;
  const char* who[] = {"P01", "P02", "P03", "P04"};
  for (int i = 0; i < 4; ++i) {
    const double base = 2 + i;  // each participant uses the scale their own way
    rows.push_back(row(who[i], "a", base, 1));
    rows.push_back(row(who[i], "a", base + 1, 2));
    rows.push_back(row(who[i], "b", base + 2, 3));
    rows.push_back(row(who[i], "b", base + 2, 4));
    rows.push_back(row(who[i], "c", base + 4, 5));
    rows.push_back(row(who[i], "c", base + 5, 6));
  }
  return rows;
}

TrialReportOptions knob_options() {
  TrialReportOptions o;
  o.factor = "knob";
  o.levels = {"a", "b", "c"};
  return o;
}

bool has_note(const TrialReport& r, const std::string& part) {
  return std::any_of(r.notes.begin(), r.notes.end(), [&](const std::string& n) { return n.find(part) != n.npos; });
}

TEST(TrialReport, ComparesEachParticipantsMedianRatingAcrossTheLevelsWithFriedmanAndWilcoxon) {
  const TrialReport r = trial_report(ranked_rows(), knob_options());
  ASSERT_EQ(r.levels.size(), 3u);
  EXPECT_EQ(r.participants, (std::vector<std::string>{"P01", "P02", "P03", "P04"}));
  EXPECT_EQ(r.trials, 24u);
  // Knob a: trials (2,3), (3,4), (4,5), (5,6): mean 3.5 over trials and over participants.
  EXPECT_EQ(r.levels[0].trials, 8u);
  EXPECT_DOUBLE_EQ(r.levels[0].rating_mean.at("sam_valence"), 4.0);
  const ParticipantMean& a = r.levels[0].rating_by_participant.at("sam_valence");
  EXPECT_DOUBLE_EQ(a.mean, 4.0);
  EXPECT_EQ(a.participants, 4u);
  // Participants' means 2.5, 3.5, 4.5, 5.5: SD √(5/3), t(0.975, 3) = 3.182446305.
  EXPECT_NEAR(a.high - a.mean, 3.182446305284263 * std::sqrt(5.0 / 3.0) / 2.0, 1e-9);
  EXPECT_EQ(r.levels[0].rating_values.at("sam_valence"), (std::vector<double>{2.5, 3.5, 4.5, 5.5}));

  ASSERT_EQ(r.scales.size(), 1u);
  const ScaleTests& t = r.scales[0];
  EXPECT_EQ(t.scale, "sam_valence");
  // Every participant ranks a, b, c as 1, 2, 3: rank sums 4, 8, 12, so
  // χ² = 12/(n·k·(k+1))·ΣR² − 3·n·(k+1) = 12/48·224 − 48 = 8 on 2 df, p = e⁻⁴.
  ASSERT_TRUE(t.tests.friedman);
  EXPECT_NEAR(t.tests.friedman->statistic, 8.0, 1e-12);
  EXPECT_EQ(t.tests.friedman->df, 2.0);
  EXPECT_NEAR(t.tests.friedman->p, std::exp(-4.0), 1e-12);
  // b and c against a: four positive differences each, the exact p 2/16.
  ASSERT_EQ(t.tests.wilcoxon.size(), 2u);
  EXPECT_EQ(t.tests.wilcoxon[0].level, "b");
  EXPECT_EQ(t.tests.wilcoxon[0].control, "a");
  ASSERT_TRUE(t.tests.wilcoxon[1].test);
  EXPECT_NEAR(t.tests.wilcoxon[1].test->p, 0.125, 1e-12);
  EXPECT_NEAR(t.tests.wilcoxon[1].p_bonferroni, 0.25, 1e-12);
  EXPECT_FALSE(t.emg);  // no biometrics recorded
}

TEST(TrialReport, TheLevelOrderPutsTheControlFirstWhateverOrderTheTrialsCameIn) {
  TrialReportOptions o = knob_options();
  o.levels = {"c", "a", "b"};
  const TrialReport r = trial_report(ranked_rows(), o);
  EXPECT_EQ(r.levels[0].level, "c");
  EXPECT_EQ(r.scales[0].tests.wilcoxon[0].control, "c");
  EXPECT_EQ(r.scales[0].tests.wilcoxon[0].level, "a");
}

TEST(TrialReport, LeavesPracticeOutAndParticipantsWithoutEveryLevelOutOfTheTests) {
  std::vector<TrialRow> rows = ranked_rows();
  TrialRow practice = row("P01", "a", 9);
  practice.practice = true;
  rows.push_back(practice);
  rows.push_back(row("P05", "a", 9));  // never felt b or c
  const TrialReport r = trial_report(rows, knob_options());
  EXPECT_EQ(r.trials, 25u);  // P05's trial counts, the practice does not
  EXPECT_EQ(r.participants.size(), 4u);
  EXPECT_TRUE(has_note(r, "participant P05 is left out")) << r.notes.front();
  EXPECT_NEAR(r.scales[0].tests.friedman->statistic, 8.0, 1e-12);
  // Over trials P05's 9 counts; over participants it does not.
  EXPECT_DOUBLE_EQ(r.levels[0].rating_mean.at("sam_valence"), (32.0 + 9.0) / 9.0);
  EXPECT_DOUBLE_EQ(r.levels[0].rating_by_participant.at("sam_valence").mean, 4.0);
}

TEST(TrialReport, ATestUndefinedOnTheDataIsLeftOutWithANote) {
  std::vector<TrialRow> rows;
  for (const char* who : {"P01", "P02", "P03"})
    for (const char* level : {"a", "b", "c"}) rows.push_back(row(who, level, 5));
  const TrialReport r = trial_report(rows, knob_options());
  EXPECT_FALSE(r.scales[0].tests.friedman);
  EXPECT_FALSE(r.scales[0].tests.wilcoxon[0].test);
  EXPECT_TRUE(has_note(r, "sam_valence: no Friedman test"));
}

TEST(TrialReport, ComparesTheMatchedSlidersWithTheReferenceKnobs) {
  std::vector<TrialRow> rows;
  const double settings[][2] = {{0.002, 0.004}, {0.003, 0.006}};  // B_vel per participant on knobs a, b
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      TrialRow r;
      r.participant = i ? "P02" : "P01";
      r.levels = {{"knob", j ? "b" : "a"}};
      r.ratings = {{"satisfaction", 2.0 + i + j}};
      r.measures = {{"slider_B_vel", settings[i][j]}, {"slider_A_pos", 0.001}, {"time_s", 10.0 + i}};
      rows.push_back(r);
    }
  TrialReportOptions o;
  o.factor = "knob";
  o.levels = {"a", "b"};
  o.references = {{"a", {{"B_vel", 0.0025}, {"A_pos", 0.0}}}, {"b", {{"B_vel", 0.004}, {"A_pos", 0.002}}}};
  const TrialReport r = trial_report(rows, o);
  const auto find = [&](const std::string& level, const std::string& parameter) {
    const auto it = std::find_if(r.matches.begin(), r.matches.end(),
                                 [&](const MatchEstimate& m) { return m.level == level && m.parameter == parameter; });
    EXPECT_NE(it, r.matches.end()) << level << " " << parameter;
    return *it;
  };
  EXPECT_EQ(r.matches.size(), 4u);
  const MatchEstimate a = find("a", "B_vel");
  EXPECT_DOUBLE_EQ(a.reference, 0.0025);
  EXPECT_DOUBLE_EQ(a.matched.mean, 0.0025);
  EXPECT_DOUBLE_EQ(a.ratio, 1.0);
  EXPECT_DOUBLE_EQ(find("b", "B_vel").ratio, 0.005 / 0.004);
  EXPECT_DOUBLE_EQ(find("b", "A_pos").ratio, 0.5);
  EXPECT_TRUE(std::isnan(find("a", "A_pos").ratio));
  EXPECT_TRUE(has_note(r, "knob a has no A_pos"));
  // Other measures are summarised per level but not matched.
  EXPECT_DOUBLE_EQ(r.levels[1].measure_by_participant.at("time_s").mean, 10.5);
  const std::string text = format_trial_report(r);
  EXPECT_NE(text.find("Matched against the reference knobs"), std::string::npos) << text;
  EXPECT_TRUE(to_json(r)["matches"][0].contains("ratio"));
}

TEST(TrialReport, CorrelatesEachScaleWithTheBiometricsOverTrials) {
  std::vector<TrialRow> rows = ranked_rows();
  for (TrialRow& r : rows) {
    r.emg_uV = -3.0 * r.ratings.at("sam_valence");  // frowning at what displeases
    if (r.trial % 2) r.sc_uS = 0.1 * r.trial;        // SC on half the trials
  }
  const TrialReport r = trial_report(rows, knob_options());
  ASSERT_TRUE(r.scales[0].emg);
  EXPECT_NEAR(r.scales[0].emg->r, -1.0, 1e-12);
  EXPECT_EQ(r.scales[0].emg->n, 24u);
  ASSERT_TRUE(r.scales[0].sc);
  EXPECT_EQ(r.scales[0].sc->n, 12u);
  EXPECT_TRUE(to_json(r)["scales"][0].contains("emg"));
}

TEST(TrialReport, RefusesDataThatCannotSupportItWithASentenceSayingWhy) {
  const auto refusal = [](const std::vector<TrialRow>& rows, const TrialReportOptions& o) {
    try {
      trial_report(rows, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::vector<TrialRow> practice = ranked_rows();
  for (TrialRow& r : practice) r.practice = true;
  EXPECT_NE(refusal(practice, knob_options()).find("all of them practice"), std::string::npos);

  TrialReportOptions other = knob_options();
  other.factor = "texture";
  EXPECT_NE(refusal(ranked_rows(), other).find("no level of factor \"texture\""), std::string::npos);

  TrialReportOptions more = knob_options();
  more.levels.push_back("d");
  EXPECT_NE(refusal(ranked_rows(), more).find("level \"d\" of knob has no analysed trials"), std::string::npos);

  TrialReportOptions fewer = knob_options();
  fewer.levels = {"a", "b"};
  EXPECT_NE(refusal(ranked_rows(), fewer).find("\"c\" of the trials is not among the levels"), std::string::npos);

  std::vector<TrialRow> one_level;
  for (const TrialRow& r : ranked_rows())
    if (r.levels.at("knob") == "a") one_level.push_back(r);
  TrialReportOptions free;
  free.factor = "knob";
  EXPECT_NE(refusal(one_level, free).find("comparing levels needs at least 2"), std::string::npos);

  std::vector<TrialRow> one_participant;
  for (const TrialRow& r : ranked_rows())
    if (r.participant == "P01") one_participant.push_back(r);
  EXPECT_NE(refusal(one_participant, knob_options()).find("at least 2 participants"), std::string::npos);
}

}  // namespace
}  // namespace knoblab::study
