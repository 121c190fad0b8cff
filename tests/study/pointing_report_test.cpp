// The pointing study's report: every figure against an independent
// computation in base R (pointing_reference.R) run at test time on the same
// tidy CSV, key for key; what is left out (practice, biometrics not
// recorded, tests undefined on the data) and what is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <format>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/study/pointing_report.hpp"
#include "knoblab/study/tidy.hpp"
#include "pointing_data.hpp"
#include "r_reference.hpp"

namespace knoblab::study {
namespace {

using nlohmann::json;

using test::expect_same;

// Through the CSV, as the CLI will: what R reads is what the report reads.
std::vector<PointingRow> through_csv(const std::vector<PointingRow>& rows) {
  std::stringstream s;
  write_pointing_csv(s, rows);
  return read_pointing_csv(s);
}

bool has_note(const PointingReport& r, const std::string& part) {
  return std::any_of(r.notes.begin(), r.notes.end(), [&](const std::string& n) { return n.find(part) != n.npos; });
}

TEST(PointingReport, EveryFigureMatchesAnIndependentComputationInR) {
  // 12 participants × 7 renderings × 2 amplitudes × 2 widths × 3 analysed
  // blocks × 3 acquisitions, a practice block, biometrics with gaps, and
  // P99 without the last rendering.
  const auto rows = through_csv(test::synthetic_pointing({.incomplete_participant = true}));
  const PointingReport report = pointing_report(rows);
  const json ours = to_json(report);

  ASSERT_EQ(report.renderings.size(), 7u);
  EXPECT_EQ(report.renderings.front().rendering, "not-rendered");  // the rows' first, here the control
  EXPECT_EQ(report.participants.size(), 12u);
  EXPECT_EQ(report.acquisitions, 12u * 7 * 4 * 3 * 3 + 6 * 4 * 3 * 3);
  EXPECT_EQ(report.trials, report.acquisitions / 3);
  EXPECT_TRUE(has_note(report, "participant P99 is left out of the ANOVA and the rating tests"));
  for (const auto& g : report.renderings) {
    ASSERT_EQ(g.cells.size(), 4u) << g.rendering;
    EXPECT_TRUE(g.fitts_line) << g.rendering;
  }
  // The synthetic effects are there to be found.
  EXPECT_LT(report.anova_movement_time.p, 1e-6);
  ASSERT_TRUE(report.friedman_rating);
  EXPECT_LT(report.friedman_rating->p, 1e-3);
  ASSERT_EQ(report.wilcoxon_rating.size(), 6u);
  for (const auto& w : report.wilcoxon_rating) ASSERT_TRUE(w.test) << w.level;
  // Ties in the medians of 12 participants: the exact distribution of the tied ranks.
  EXPECT_EQ(report.wilcoxon_rating[1].test->method, stats::WilcoxonMethod::exact);
  ASSERT_TRUE(report.correlations.movement_time_rating && report.correlations.rating_emg &&
              report.correlations.rating_sc);
  EXPECT_GT(report.correlations.rating_emg->r, 0.3);

  const json ref = test::r_pointing_reference(rows);
  const std::size_t compared = expect_same(ours, ref, "report");
  // Per rendering 4 cells × 10 and 18 of its own; the ANOVA's 10, the
  // Friedman test's 4, 6 Wilcoxon tests × 7, 3 correlations × 3, the counts.
  EXPECT_EQ(compared, 7u * (4 * 10 + 18) + 10 + 4 + 6 * 7 + 3 * 3 + 2);
}

TEST(PointingReport, AGivenLevelOrderAndTheNormalApproximationMatchR) {
  // 16 participants: more than 13 pairs with ties, so the Wilcoxon tests
  // take the normal approximation; no biometrics; the control named first
  // although the rows name another rendering first.
  const auto rows = through_csv(
      test::synthetic_pointing({.participants = 16, .analysed_blocks = 2, .seed = 11, .biometrics = false}));
  std::vector<std::string> order = test::study3_renderings();
  std::rotate(order.begin(), order.begin() + 2, order.end());  // "high-friction" is the control here
  const PointingReport report = pointing_report(rows, {.rendering_order = order});
  EXPECT_EQ(report.renderings.front().rendering, "high-friction");
  EXPECT_EQ(report.wilcoxon_rating.front().control, "high-friction");
  bool normal = false;
  for (const auto& w : report.wilcoxon_rating) normal = normal || (w.test && w.test->method == stats::WilcoxonMethod::normal);
  EXPECT_TRUE(normal);
  EXPECT_FALSE(report.correlations.rating_emg);
  EXPECT_FALSE(report.correlations.rating_sc);
  const json ours = to_json(report);
  EXPECT_FALSE(ours.at("correlations").contains("rating_emg"));
  expect_same(ours, test::r_pointing_reference(rows, order), "report");
}

TEST(PointingReport, TestsUndefinedOnTheDataAreLeftOutWithANoteAsInR) {
  auto rows = test::synthetic_pointing({.participants = 5, .analysed_blocks = 1, .biometrics = false});
  for (auto& r : rows) r.rating = 5;  // everyone rates everything the same
  rows = through_csv(rows);
  const PointingReport report = pointing_report(rows);
  EXPECT_FALSE(report.friedman_rating);
  for (const auto& w : report.wilcoxon_rating) EXPECT_FALSE(w.test);
  EXPECT_FALSE(report.correlations.movement_time_rating);
  EXPECT_TRUE(has_note(report, "no Friedman test"));
  EXPECT_TRUE(has_note(report, "no Wilcoxon test of \"low-friction\" against \"not-rendered\""));
  EXPECT_TRUE(has_note(report, "no Spearman correlation of movement time with rating"));
  const json ours = to_json(report);
  EXPECT_FALSE(ours.contains("friedman_rating"));
  EXPECT_FALSE(ours["wilcoxon_rating"][0].contains("p"));
  expect_same(ours, test::r_pointing_reference(rows), "report");
}

TEST(PointingReport, PracticeRowsAreLeftOut) {
  const auto rows = test::synthetic_pointing({.participants = 4, .analysed_blocks = 1});
  std::vector<PointingRow> analysed;
  for (const auto& r : rows)
    if (!r.practice) analysed.push_back(r);
  ASSERT_LT(analysed.size(), rows.size());
  EXPECT_EQ(to_json(pointing_report(rows)), to_json(pointing_report(analysed)));
}

TEST(PointingReport, TheRenderingsFiguresAreTheMeansOfItsCells) {
  const PointingReport r = pointing_report(test::synthetic_pointing({.participants = 3, .analysed_blocks = 1}));
  for (const auto& g : r.renderings) {
    double we = 0, ide = 0, tp = 0;
    for (const auto& c : g.cells) {
      EXPECT_NEAR(c.We_deg, 4.133 * c.endpoint_sd_deg, 1e-12 * c.We_deg);
      EXPECT_NEAR(c.IDe_bits, std::log2(c.amplitude_deg / c.We_deg + 1), 1e-12);
      EXPECT_NEAR(c.throughput_bits_per_s, c.IDe_bits / c.movement_time_s, 1e-12);
      we += c.We_deg / 4, ide += c.IDe_bits / 4, tp += c.throughput_bits_per_s / 4;
    }
    EXPECT_NEAR(g.We_deg, we, 1e-12);
    EXPECT_NEAR(g.IDe_bits, ide, 1e-12);
    EXPECT_NEAR(g.throughput_bits_per_s, tp, 1e-12);
  }
  // Table 27's Welford IDs for 30°: 1.3 (W = 1.4°), 0.5 (W = 11.3°).
  EXPECT_NEAR(r.renderings[0].cells[0].welford_id, 1.3, 0.05);
  EXPECT_NEAR(r.renderings[0].cells[1].welford_id, 0.5, 0.05);
}

// The message of what `f` throws, or "" when it does not throw.
template <typename F>
std::string refusal(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PointingReport, TooFewParticipantsWithEveryRenderingAreRefused) {
  auto rows = test::synthetic_pointing({.participants = 3, .analysed_blocks = 1});
  // P03 never did few-detents: 2 complete participants.
  std::erase_if(rows, [](const PointingRow& r) { return r.participant == "P03" && r.rendering == "few-detents"; });
  const std::string why = refusal([&] { pointing_report(rows); });
  EXPECT_NE(why.find("needs at least 3 participants with trials in every rendering"), std::string::npos) << why;
  EXPECT_NE(why.find("2 have: P01, P02"), std::string::npos) << why;
}

TEST(PointingReport, ACellWithOneEndPointIsRefused) {
  auto rows = test::synthetic_pointing({.participants = 3, .analysed_blocks = 1});
  std::erase_if(rows, [](const PointingRow& r) {
    return r.rendering == "low-inertia" && r.amplitude_deg == 200 && r.width_deg == 1.4 && !r.practice &&
           !(r.participant == "P01" && r.acquisition == 1);
  });
  const std::string why = refusal([&] { pointing_report(rows); });
  EXPECT_NE(why.find("rendering \"low-inertia\", A = 200°, W = 1.4° has 1 end point"), std::string::npos) << why;
}

TEST(PointingReport, OtherUnsupportableDataIsRefused) {
  auto rows = test::synthetic_pointing({.participants = 3, .analysed_blocks = 1});
  std::vector<PointingRow> practice_only, one_rendering;
  for (const auto& r : rows) {
    if (r.practice) practice_only.push_back(r);
    if (r.rendering == "few-detents") one_rendering.push_back(r);
  }
  EXPECT_NE(refusal([&] { pointing_report(practice_only); }).find("no rows to analyse"), std::string::npos);
  EXPECT_NE(refusal([&] { pointing_report(one_rendering); }).find("needs at least 2"), std::string::npos);
  EXPECT_NE(refusal([&] {
              pointing_report(rows, {.rendering_order = {"not-rendered", "low-friction"}});
            }).find("rendering \"high-friction\" of the rows is not among the levels given"),
            std::string::npos);
  auto order = test::study3_renderings();
  order.push_back("phantom");
  EXPECT_NE(refusal([&] { pointing_report(rows, {.rendering_order = order}); })
                .find("rendering \"phantom\" of the rendering order has no analysed rows"),
            std::string::npos);
  // A cell whose end points are all the same has no effective width.
  for (auto& r : rows)
    if (r.rendering == "not-rendered" && r.amplitude_deg == 30 && r.width_deg == 11.3) r.endpoint_deg = 0.5;
  EXPECT_NE(refusal([&] { pointing_report(rows); }).find("rendering \"not-rendered\", A = 30°, W = 11.3°"),
            std::string::npos);
}

TEST(PointingReport, TheTextReportHasAFittsTablePerRenderingAndTheAnovaTable) {
  const PointingReport r = pointing_report(test::synthetic_pointing({.participants = 4, .analysed_blocks = 1}));
  const std::string text = format_pointing_report(r);
  for (const auto& name : test::study3_renderings()) EXPECT_NE(text.find("\n" + name + ": "), std::string::npos) << name;
  EXPECT_NE(text.find("IDe (bits)  TP (bits/s)"), std::string::npos) << text;
  EXPECT_NE(text.find("repeated-measures ANOVA"), std::string::npos) << text;
  EXPECT_NE(text.find("  rendering "), std::string::npos) << text;
  EXPECT_NE(text.find("  error     "), std::string::npos) << text;
  EXPECT_NE(text.find("Huynh–Feldt ε = "), std::string::npos) << text;
  EXPECT_NE(text.find("Friedman χ²(6, N = 4)"), std::string::npos) << text;
  EXPECT_NE(text.find("rating with EMG"), std::string::npos) << text;
}

}  // namespace
}  // namespace knoblab::study
