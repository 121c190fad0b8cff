// The plot module's measuring and placing: text widths and fitting, ticks,
// legends, and the layout that keeps everything on the page.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "knoblab/fit/plot/layout.hpp"
#include "knoblab/fit/plot/legend.hpp"
#include "knoblab/fit/plot/text.hpp"
#include "knoblab/fit/plot/ticks.hpp"

namespace knoblab::fit::plot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Series make(std::string name, std::string label, Mark mark, std::vector<double> x, std::vector<double> y,
            int rank = 0) {
  Series s;
  s.name = std::move(name);
  s.label = std::move(label);
  s.mark = mark;
  s.legend_rank = rank;
  s.x = std::move(x);
  s.y = std::move(y);
  return s;
}

TEST(FigureText, WidthsFollowTheFontsAdvanceWidthsAndScriptsAreSmaller) {
  EXPECT_NEAR(width_em("H"), 1540.0 / 2048.0, 1e-12);
  EXPECT_GT(width_em("MMMM"), 2.5 * width_em("iiii"));
  EXPECT_NEAR(width_em("τ#dpos#u"), width_em("τ") + kScriptScale * width_em("pos"), 1e-12);
  EXPECT_NEAR(width_em("θ\u0307"), width_em("θ"), 1e-12);  // a combining dot takes no room
  EXPECT_NEAR(width_mm("H", 72.0), 25.4 * 1540.0 / 2048.0, 1e-9);
}

TEST(FigureText, RunsSplitScriptsAndAnEscapedHashIsOneHash) {
  const auto r = runs("τ#dpos#u = 5 ##3");
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].text, "τ");
  EXPECT_EQ(r[0].level, 0);
  EXPECT_EQ(r[1].text, "pos");
  EXPECT_EQ(r[1].level, -1);
  EXPECT_EQ(r[2].text, " = 5 #3");
  EXPECT_EQ(r[2].level, 0);
  EXPECT_EQ(plain(escape("knob #3")), "knob #3");
}

TEST(FigureText, ALineTooLongIsShrunkFirstAndWrappedOnlyBelowTheSmallestSize) {
  const std::string title = "Knob 3 — torque against position, fitted by the thesis model";
  const double w10 = width_mm(title, 10.0);
  // A little too long: one line, smaller, no smaller than the minimum.
  FittedText ft = fit_text(title, 0.9 * w10, 10.0, 8.0, 2);
  ASSERT_EQ(ft.lines.size(), 1u);
  EXPECT_NEAR(ft.size_pt, 9.0, 1e-9);
  // Far too long: wrapped at the minimum size, every line within the width.
  ft = fit_text(title, 0.5 * w10, 10.0, 8.0, 2);
  EXPECT_EQ(ft.size_pt, 8.0);
  ASSERT_EQ(ft.lines.size(), 2u);
  for (const std::string& l : ft.lines) EXPECT_LE(width_mm(l, ft.size_pt), 0.5 * w10) << l;
  // Too long for the lines allowed: smaller still, until it fits.
  ft = fit_text(title, 0.2 * w10, 10.0, 8.0, 2);
  EXPECT_LT(ft.size_pt, 8.0);
  EXPECT_LE(ft.lines.size(), 2u);
  for (const std::string& l : ft.lines) EXPECT_LE(width_mm(l, ft.size_pt), 0.2 * w10) << l;
  // Short enough: as it is.
  ft = fit_text("Short", 100.0, 10.0, 8.0, 2);
  EXPECT_EQ(ft.lines, std::vector<std::string>{"Short"});
  EXPECT_EQ(ft.size_pt, 10.0);
}

TEST(Ticks, AreRoundNumbersInsideTheRangeLabelledWithTrueMinusSigns) {
  Ticks t = nice_ticks(-2.3, 7.9, 6);
  EXPECT_EQ(t.step, 2.0);
  EXPECT_EQ(t.at, (std::vector<double>{-2, 0, 2, 4, 6}));
  EXPECT_EQ(t.labels, (std::vector<std::string>{"\u22122", "0", "2", "4", "6"}));
  t = nice_ticks(-4.3, 5.9, 5);  // 2.04 a step: 2.5, with a decimal
  EXPECT_EQ(t.labels, (std::vector<std::string>{"\u22122.5", "0.0", "2.5", "5.0"}));
  t = nice_ticks(0.0, 10.0, 4);
  EXPECT_EQ(t.labels, (std::vector<std::string>{"0.0", "2.5", "5.0", "7.5", "10.0"}));
  t = nice_ticks(-0.031, 0.029, 6);
  EXPECT_EQ(t.step, 0.01);
  EXPECT_EQ(t.labels.front(), "\u22120.03");
  EXPECT_EQ(t.labels[3], "0.00");
  // A narrow range still gets two ticks.
  t = nice_ticks(0.99, 1.01, 1);
  EXPECT_GE(t.at.size(), 2u);
  for (const double v : t.at) EXPECT_TRUE(v >= 0.99 && v <= 1.01) << v;
}

TEST(Legend, ListsOnlyLabelledSeriesThatDrawSomethingOnceByRank) {
  Panel p;
  p.series.push_back(make("raw", "raw τ", Mark::Dots, {1, 2}, {3, 4}, 0));
  p.series.push_back(make("nothing", "all NaN", Mark::Line, {1, 2}, {kNaN, kNaN}, 1));
  p.series.push_back(make("empty", "no points", Mark::Dots, {}, {}, 1));
  p.series.push_back(make("zero", "", Mark::Line, {1, 2}, {0, 0}, 0));
  p.series.push_back(make("band_upper", "95% band", Mark::Dashed, {1, 2}, {1, 1}, 2));
  p.series.push_back(make("band_lower", "95% band", Mark::Dashed, {1, 2}, {-1, -1}, 2));
  p.series.push_back(make("fit", "fitted τ", Mark::Line, {1, 2}, {0, 1}, 1));
  p.series.push_back(make("limits", "stick band", Mark::VLines, {-0.5, 0.5}, {}, 4));
  Series fill = make("hole", "band with no lower edge", Mark::Fill, {1, 2}, {1, 1}, 3);
  fill.y_low = {kNaN, kNaN};
  p.series.push_back(fill);
  const auto e = legend_entries(p);
  std::vector<std::string> labels;
  for (const auto& x : e) labels.push_back(x.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"raw τ", "fitted τ", "95% band", "stick band"}));
  EXPECT_EQ(e[2].mark, Mark::Dashed);
}

// A figure meant to crowd the page: long title and subtitle, long headings
// and labels, legends with long labels, three rows.
Figure crowded() {
  Figure f;
  f.title = "A knob whose name is very long indeed, recorded on the bench in the lab on a long afternoon — "
            "torque against position with every part of Eq. 6 and both of its 95% bands";
  f.subtitle = "thesis6 fit, 123456 samples, RMSE 0.123 mN·m, fit 97.1 %, detents, and some more words to "
               "make the subtitle run over the width of any figure narrower than a poster";
  for (int k = 0; k < 3; ++k) {
    Panel p;
    p.name = "p" + std::to_string(k);
    p.heading = "Position part: τ#dpos#u = τ − τ#dacc#u − τ#dvel#u (no detents fitted: fitted τ#dpos#u = 0) "
                "and a heading that goes on";
    p.xlabel = "position θ (deg), the angle of the knob from where the capture began";
    p.ylabel = "the position part of the torque τ#dpos#u (mN·m)";
    std::vector<double> x, y;
    for (int i = 0; i <= 100; ++i) x.push_back(-12345.0 + 246.9 * i), y.push_back(1e4 * std::sin(i * 0.1));
    p.series.push_back(make("raw", "raw τ#dpos#u, the position part of every sample", Mark::Dots, x, y, 0));
    p.series.push_back(make("fit", "fitted τ#dpos#u", Mark::Line, x, y, 1));
    p.series.push_back(make("limits", "stick band ±Δv", Mark::VLines, {-100.0, 100.0}, {}, 2));
    f.panels.push_back(std::move(p));
  }
  return f;
}

bool inside(const Box& b, const Layout& l) {
  constexpr double e = 1e-6;
  return b.x0 >= -e && b.y0 >= -e && b.x1 <= l.width_mm + e && b.y1 <= l.height_mm + e;
}

bool overlap(const Box& a, const Box& b) {
  constexpr double e = 0.05;  // mm
  return a.x0 < b.x1 - e && b.x0 < a.x1 - e && a.y0 < b.y1 - e && b.y0 < a.y1 - e;
}

TEST(FigureLayout, NothingOfACrowdedFigureLeavesThePageOrOverlaps) {
  const Figure f = crowded();
  for (const auto& [w, h] : {std::pair{160.0, 175.0}, std::pair{80.0, 70.0}, std::pair{300.0, 100.0},
                             std::pair{160.0, 0.0}, std::pair{60.0, 50.0}, std::pair{40.0, 40.0}}) {
    const Layout l = layout_figure(f, w, h);
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    ASSERT_EQ(l.panels.size(), 3u);
    for (const TextItem& t : l.texts) EXPECT_TRUE(inside(extent(t), l)) << t.text;
    for (std::size_t a = 0; a < l.texts.size(); ++a)
      for (std::size_t b = a + 1; b < l.texts.size(); ++b)
        EXPECT_FALSE(overlap(extent(l.texts[a]), extent(l.texts[b]))) << l.texts[a].text << " | " << l.texts[b].text;
    for (std::size_t a = 0; a < l.panels.size(); ++a) {
      const Box& box = l.panels[a].box;
      EXPECT_TRUE(inside(box, l));
      // Room for the data, however small the page (40 mm: the smallest allowed).
      const double least = w >= 60.0 ? 5.0 : 0.5;
      EXPECT_GT(box.width(), least);
      EXPECT_GT(box.height(), least);
      for (const TextItem& t : l.texts) EXPECT_FALSE(overlap(extent(t), box)) << t.text;
      for (const LegendSample& s : l.panels[a].legend) {
        EXPECT_TRUE(inside(s.box, l));
        EXPECT_GE(s.box.x0, box.x1);
      }
      for (std::size_t b = a + 1; b < l.panels.size(); ++b) EXPECT_FALSE(overlap(box, l.panels[b].box));
    }
  }
}

TEST(FigureLayout, ALongTitleIsShrunkThenWrappedToThePageWidth) {
  Figure f = crowded();
  const Layout l = layout_figure(f, 160.0, 175.0);
  double title_lines = 0, title_size = 0;
  for (const TextItem& t : l.texts)
    if (t.text.size() > 10 && f.title.find(t.text) != std::string::npos && t.anchor == Anchor::Middle)
      ++title_lines, title_size = t.size_pt;
  EXPECT_EQ(title_lines, 2);
  EXPECT_GE(title_size, 8.0);  // 80 % of 10 pt, not less, when two lines take it
}

TEST(FigureLayout, DataRangesArePaddedAndAFixedYRangeIsKept) {
  Figure f;
  Panel p;
  p.series.push_back(make("a", "", Mark::Dots, {0.0, 10.0}, {-1.0, 3.0}));
  f.panels.push_back(p);
  p.y_lo = -0.5;
  p.y_hi = 0.5;
  f.panels.push_back(p);
  const Layout l = layout_figure(f, 160.0, 0.0);
  EXPECT_DOUBLE_EQ(l.panels[0].x_lo, -0.2);
  EXPECT_DOUBLE_EQ(l.panels[0].x_hi, 10.2);
  EXPECT_DOUBLE_EQ(l.panels[0].y_lo, -1.2);
  EXPECT_DOUBLE_EQ(l.panels[0].y_hi, 3.2);
  EXPECT_DOUBLE_EQ(l.panels[1].y_lo, -0.5);
  EXPECT_DOUBLE_EQ(l.panels[1].y_hi, 0.5);
  EXPECT_DOUBLE_EQ(l.height_mm, 135.0);  // two rows
}

Figure text_page(std::size_t paragraphs) {
  Figure f;
  f.title = "what the thesis model leaves out";
  f.text.table = {{"model", "RMS\nmN·m", "held-out\nRMS mN·m", "fit %"},
                  {"base (Eq. 6)", "9.57", "9.61", "80.1"},
                  {"+ detent_shape (final)", "1.5", "1.52", "96.3"}};
  for (std::size_t k = 0; k < paragraphs; ++k)
    f.text.paragraphs.push_back(std::to_string(k + 1) + ". A sentence about a finding that runs on for a while, "
                                                        "so that it has to be wrapped onto several lines of the page.");
  f.text.notes = {"A note in smaller type, also long enough to wrap at least once on a figure of ordinary width."};
  return f;
}

TEST(FigureLayout, ATextPageFitsItsPageByShrinkingAndIsAsTallAsItsTextOtherwise) {
  for (const double h : {100.0, 0.0}) {
    const Layout l = layout_figure(text_page(h > 0.0 ? 30 : 12), 160.0, h);
    SCOPED_TRACE(h);
    EXPECT_FALSE(l.rules.empty());  // the table's rule
    double paragraph_pt = 0;
    for (const TextItem& t : l.texts) {
      EXPECT_TRUE(inside(extent(t), l)) << t.text;
      if (t.text.starts_with("1. ")) paragraph_pt = t.size_pt;
    }
    if (h > 0.0) {
      EXPECT_LT(paragraph_pt, 8.0);  // shrunk to fit 100 mm
    } else {
      EXPECT_DOUBLE_EQ(paragraph_pt, 8.0);
      EXPECT_GT(l.height_mm, 100.0);
    }
  }
}

}  // namespace
}  // namespace knoblab::fit::plot
