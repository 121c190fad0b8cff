// The per-trial report's figures: a rating figure per scale and a match
// figure per slider, each written as PDF, SVG, PNG and CSV, drawing the
// report's numbers (the participants' values, their mean and interval, the
// settings over the reference).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/study/trial_plots.hpp"
#include "knoblab/study/trial_report.hpp"
#include "png_image.hpp"

namespace knoblab::study {
namespace {

namespace fs = std::filesystem;

// Three participants matching knobs a and b: a's B_vel is 2 mN·m·s/rad.
TrialReport matching_report() {
  std::vector<TrialRow> rows;
  for (int i = 0; i < 3; ++i)
    for (const char* knob : {"a", "b"}) {
      TrialRow r;
      r.participant = "P0" + std::to_string(i + 1);
      r.levels = {{"knob", knob}};
      r.ratings = {{"satisfaction", 2.0 + i}, {"sam_valence", std::string(knob) == "a" ? 3.0 + i : 6.0}};
      r.measures = {{"slider_B_vel", 0.001 * (1 + i)}};
      rows.push_back(r);
    }
  TrialReportOptions o;
  o.factor = "knob";
  o.levels = {"a", "b"};
  o.references = {{"a", {{"B_vel", 0.002}}}, {"b", {{"B_vel", 0.004}}}};
  return trial_report(rows, o);
}

fit::plot::Series series(const std::vector<fit::plot::NamedFigure>& figures, const std::string& stem,
                         const std::string& name) {
  for (const auto& f : figures)
    if (f.stem == stem)
      for (const auto& s : f.figure.panels.at(0).series)
        if (s.name == name) return s;
  throw std::runtime_error("no series " + name + " in " + stem);
}

TEST(TrialPlots, DrawARatingFigurePerScaleAndAMatchFigurePerSliderWithTheReportsNumbers) {
  const TrialReport r = matching_report();
  const auto figures = trial_figures(r);
  std::set<std::string> stems;
  for (const auto& f : figures) stems.insert(f.stem);
  EXPECT_EQ(stems, (std::set<std::string>{"rating_satisfaction", "rating_sam_valence", "match_B_vel"}));

  // Knob b's valence mean is 6 (every participant rated it 6); a's interval is drawn.
  EXPECT_EQ(series(figures, "rating_sam_valence", "b_mean").y, (std::vector<double>{6.0}));
  const auto bar = series(figures, "rating_sam_valence", "a_ci95").y;
  EXPECT_DOUBLE_EQ(bar[0], r.levels[0].rating_by_participant.at("sam_valence").low);
  // The settings 1, 2, 3 mN·m·s/rad over a's 2: 0.5, 1, 1.5; over b's 4: 0.25 … 0.75.
  const auto dots = series(figures, "match_B_vel", "participants").y;
  EXPECT_EQ(dots, (std::vector<double>{0.5, 1.0, 1.5, 0.25, 0.5, 0.75}));
  EXPECT_DOUBLE_EQ(series(figures, "match_B_vel", "b_mean").y[0], 0.5);
  EXPECT_EQ(series(figures, "match_B_vel", "perfect_match").y, (std::vector<double>{1.0, 1.0}));
}

TEST(TrialPlots, WritesEachFigureAsPdfSvgPngAndItsCsv) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("knoblab_trial_plots_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto files = write_trial_plots(matching_report(), dir);
  std::set<std::string> names;
  for (const fs::path& f : files) {
    names.insert(f.filename().string());
    EXPECT_GT(fs::file_size(f), 300u) << f;
  }
  EXPECT_EQ(names.size(), 12u);
  EXPECT_TRUE(names.contains("match_B_vel.png"));
  const auto image = knoblab::testing::decode_png(dir / "rating_satisfaction.png");
  EXPECT_GT(image.width, 100u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace knoblab::study
