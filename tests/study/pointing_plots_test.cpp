// The pointing report's figures: every file written and drawn (PNGs decoded
// and looked at for their colours), the figures holding the report's
// numbers, their CSVs, and rows that do not fit the report refused.
//
// KNOBLAB_REPORT_EXAMPLE=dir keeps the example figures in `dir` to look at.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/study/pointing_plots.hpp"
#include "knoblab/study/pointing_report.hpp"
#include "pointing_data.hpp"
#include "png_image.hpp"

namespace knoblab::study {
namespace {

namespace fs = std::filesystem;
using knoblab::testing::decode_png;
using knoblab::testing::Image;

class PointingPlots : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // The pid too: two builds' tests on one machine must not share a directory.
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("knoblab_pointing_plots_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

const std::vector<PointingRow>& rows() {
  static const auto r = test::synthetic_pointing({.incomplete_participant = true});
  return r;
}

const PointingReport& report() {
  static const PointingReport r = pointing_report(rows());
  return r;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Pixels within 20 of `c` in every channel (antialiased edges are not).
std::size_t pixels_of(const Image& im, std::array<int, 3> c) {
  std::size_t n = 0;
  for (std::uint32_t y = 0; y < im.height; ++y)
    for (std::uint32_t x = 0; x < im.width; ++x) {
      const auto p = im.at(x, y);
      n += std::abs(p[0] - c[0]) <= 20 && std::abs(p[1] - c[1]) <= 20 && std::abs(p[2] - c[2]) <= 20 ? 1 : 0;
    }
  return n;
}

TEST_F(PointingPlots, WritesEachFigureAsPdfSvgPngAndItsCsv) {
  const auto files = write_pointing_plots(report(), rows(), dir_ / "plots");
  std::set<std::string> names;
  for (const fs::path& f : files) {
    names.insert(f.filename().string());
    ASSERT_TRUE(fs::is_regular_file(f)) << f;
    const std::string bytes = read_bytes(f);
    EXPECT_GT(bytes.size(), 500u) << f;
    if (f.extension() == ".pdf") {
      EXPECT_TRUE(bytes.starts_with("%PDF-")) << f;
    }
    if (f.extension() == ".svg") {
      EXPECT_NE(bytes.find("<svg"), std::string::npos) << f;
    }
  }
  std::set<std::string> expected;
  for (const char* stem : {"movement_time", "fitts", "rating"})
    for (const char* ext : {".pdf", ".svg", ".png", ".csv"}) expected.insert(std::string(stem) + ext);
  EXPECT_EQ(names, expected);
  if (const char* keep = std::getenv("KNOBLAB_REPORT_EXAMPLE")) {
    fs::create_directories(keep);
    for (const fs::path& f : files)
      fs::copy_file(f, fs::path(keep) / f.filename(), fs::copy_options::overwrite_existing);
  }
}

TEST_F(PointingPlots, ThePngsAreDrawnWithEveryRenderingsColourAndTheParticipantsGrey) {
  fit::plot::FigureOptions png;
  png.formats = {fit::plot::Format::Png};
  png.dpi = 100;
  write_pointing_plots(report(), rows(), dir_, png);
  // tab10's blue (the control) … pink (the seventh), and the light grey.
  const std::vector<std::array<int, 3>> colours = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44}, {214, 39, 40},
                                                   {148, 103, 189}, {140, 86, 75},  {227, 119, 194}};
  for (const char* stem : {"movement_time", "fitts", "rating"}) {
    const Image im = decode_png(dir_ / (std::string(stem) + ".png"));
    EXPECT_EQ(im.width, 630u) << stem;  // 160 mm at 100 dpi
    std::size_t white = pixels_of(im, {255, 255, 255});
    EXPECT_LT(white, 0.97 * im.width * im.height) << stem << ": nearly blank";
    for (const auto& c : colours) EXPECT_GT(pixels_of(im, c), 10u) << stem << " lacks " << c[0] << "," << c[1];
    if (std::string(stem) != "fitts") {
      EXPECT_GT(pixels_of(im, {190, 190, 190}), 100u) << stem;
    }
  }
}

// Copies: a reference returned beside a temporary name argument makes GCC
// warn (-Wdangling-reference) although it points into `figures`.
fit::plot::Panel panel(const std::vector<fit::plot::NamedFigure>& figures, const std::string& stem) {
  for (const auto& f : figures)
    if (f.stem == stem) return f.figure.panels.at(0);
  throw std::runtime_error("no figure " + stem);
}

fit::plot::Series series(const fit::plot::Panel& p, const std::string& name) {
  for (const auto& s : p.series)
    if (s.name == name) return s;
  throw std::runtime_error("no series " + name + " in " + p.name);
}

TEST_F(PointingPlots, TheFiguresDrawTheReportsNumbers) {
  const auto figures = pointing_figures(report(), rows());
  const PointingRendering& control = report().renderings[0];
  const auto mt = panel(figures, "movement_time");
  EXPECT_EQ(series(mt, "participants").y.size(), 12u * 7);  // P99 is not in the ANOVA
  EXPECT_EQ(series(mt, "not_rendered_mean").y, std::vector{control.movement_time_by_participant.mean});
  EXPECT_EQ(series(mt, "many_detents_ci95").y, (std::vector{report().renderings[6].movement_time_by_participant.low,
                                                            report().renderings[6].movement_time_by_participant.high}));
  EXPECT_EQ(series(mt, "many_detents_ci95").x, (std::vector{7.0, 7.0}));
  EXPECT_NE(mt.xlabel.find("1 not-rendered, 2 low-friction"), std::string::npos) << mt.xlabel;
  EXPECT_NE(mt.heading.find("Huynh–Feldt"), std::string::npos) << mt.heading;

  const auto fitts = panel(figures, "fitts");
  const auto line = series(fitts, "few_detents_line");
  const auto& fl = *report().renderings[5].fitts_line;
  ASSERT_EQ(line.x.size(), 2u);
  EXPECT_DOUBLE_EQ(line.y[1], fl.intercept + fl.slope * line.x[1]);
  EXPECT_EQ(series(fitts, "few_detents_cells").x.size(), 4u);

  const auto rating = panel(figures, "rating");
  EXPECT_EQ(series(rating, "low_inertia_mean").y, std::vector{report().renderings[3].rating_by_participant.mean});
  EXPECT_NE(rating.heading.find("Friedman"), std::string::npos);
}

TEST_F(PointingPlots, EachCsvHoldsThePlottedDataWithItsUnits) {
  fit::plot::FigureOptions png;
  png.formats = {fit::plot::Format::Png};
  png.dpi = 100;
  write_pointing_plots(report(), rows(), dir_, png);
  const std::string mt = read_bytes(dir_ / "movement_time.csv");
  EXPECT_TRUE(mt.starts_with("panel,series,rendering_number,movement_time_s\n")) << mt.substr(0, 80);
  EXPECT_NE(mt.find("\nmovement_time,not_rendered_mean,1,"), std::string::npos);
  EXPECT_TRUE(read_bytes(dir_ / "fitts.csv").starts_with("panel,series,IDe_bits,movement_time_s\n"));
  EXPECT_TRUE(read_bytes(dir_ / "rating.csv").starts_with("panel,series,rendering_number,rating\n"));
}

TEST_F(PointingPlots, RowsThatDoNotFitTheReportAreRefused) {
  std::vector<PointingRow> fewer;
  for (const auto& r : rows())
    if (!(r.participant == "P02" && r.rendering == "high-inertia")) fewer.push_back(r);
  EXPECT_THROW(pointing_figures(report(), fewer), std::invalid_argument);
  fit::plot::FigureOptions bad;
  bad.dpi = 10;
  EXPECT_THROW(write_pointing_plots(report(), rows(), dir_, bad), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_));
}

}  // namespace
}  // namespace knoblab::study
