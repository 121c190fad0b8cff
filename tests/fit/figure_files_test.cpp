// write_figure(): each format is a whole, valid file of its kind with real
// text (PDF: embedded fonts and text operators; SVG: XML with <text>
// elements naming the labels), the PNG has its printed size at the dpi, and
// the CSV beside it has one row per plotted point under named columns.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "figure_checks.hpp"
#include "knoblab/fit/plot/figure_files.hpp"
#include "knoblab/fit/plot/layout.hpp"
#include "png_image.hpp"

namespace knoblab::fit::plot {
namespace {

namespace fs = std::filesystem;
using knoblab::testing::file_bytes;

// Two panels: a cloud under a line with a band, and a stick band's limits.
Figure sample_figure() {
  Figure f;
  f.title = "Knob #3 — torque against position";
  f.subtitle = "a figure for the tests";
  f.x_column = "position_deg";
  f.y_column = "torque_mNm";
  f.y_low_column = "torque_lower_mNm";
  Panel top;
  top.name = "total";
  top.heading = "Raw and fitted τ#dpos#u";
  top.xlabel = "position θ (deg)";
  top.ylabel = "τ (mN·m)";
  Series raw{"raw_torque", "raw τ", Mark::Dots, palette::kRaw, 0.4, 0, {}, {}, {}};
  Series fit{"fitted_torque", "fitted τ", Mark::Line, palette::kBlack, 0.35, 1, {}, {}, {}};
  Series band{"band", "95% band", Mark::Fill, palette::kBandLight, 0.0, 2, {}, {}, {}};
  for (int i = 0; i < 300; ++i) {
    const double x = -90.0 + 0.6 * i, y = 20.0 * std::sin(x * std::numbers::pi / 30.0);
    raw.x.push_back(x);
    raw.y.push_back(y + 3.0 * std::sin(i * 7.1));
    if (i % 3 == 0) {
      fit.x.push_back(x), fit.y.push_back(y);
      band.x.push_back(x), band.y.push_back(y + 2.0), band.y_low.push_back(y - 2.0);
    }
  }
  top.series = {band, raw, fit};
  Panel bottom;
  bottom.name = "residual";
  bottom.heading = "Residual";
  bottom.xlabel = "position θ (deg)";
  bottom.ylabel = "residual (mN·m)";
  Series res{"residual", "", Mark::Dots, palette::kRaw, 0.4, 0, {}, {}, {}};
  for (int i = 0; i < 300; ++i) res.x.push_back(-90.0 + 0.6 * i), res.y.push_back(3.0 * std::sin(i * 7.1));
  Series limits{"stick_band_limit", "stick band ±Δv", Mark::VLines, palette::kOrange, 0.3, 3, {-5.0, 5.0}, {}, {}};
  bottom.series = {res, limits};
  f.panels = {top, bottom};
  return f;
}

class FigureFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("knoblab_figure_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    opt_.width_mm = 120.0;
    opt_.height_mm = 90.0;
    opt_.dpi = 150;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  FigureOptions opt_;
};

TEST_F(FigureFiles, WritesTheFormatsAskedForInOrderAndTheCsvLast) {
  opt_.formats = {Format::Png, Format::Pdf};
  const auto files = write_figure(sample_figure(), dir_, "fig", opt_);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], dir_ / "fig.png");
  EXPECT_EQ(files[1], dir_ / "fig.pdf");
  EXPECT_EQ(files[2], dir_ / "fig.csv");
  for (const auto& f : files) EXPECT_TRUE(fs::is_regular_file(f)) << f;
  EXPECT_FALSE(fs::exists(dir_ / "fig.svg"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 3u);  // no temporary files left
}

TEST_F(FigureFiles, PdfIsWholeAtItsPrintedSizeWithEmbeddedFontsAndTextOperators) {
  opt_.formats = {Format::Pdf};
  write_figure(sample_figure(), dir_, "fig", opt_);
  const std::string pdf = file_bytes(dir_ / "fig.pdf");
  ASSERT_TRUE(pdf.starts_with("%PDF-"));
  EXPECT_NE(pdf.find("%%EOF", pdf.size() - 8), std::string::npos);
  // 120 × 90 mm in points.
  EXPECT_TRUE(knoblab::testing::pdf_contains(pdf, "/MediaBox [ 0 0 340 255 ]"));
  EXPECT_NE(pdf.find("/FontFile"), std::string::npos) << "a font is embedded";
  EXPECT_NE(pdf.find("/ToUnicode"), std::string::npos) << "its text can be searched and copied";
  // Shown as text: a text operator for each piece of the layout's text, and
  // the labels' Latin letters in the text strings (words without "fi",
  // which the font sets as a ligature).
  const auto text = knoblab::testing::pdf_text(pdf);
  EXPECT_GE(text.operators, layout_figure(sample_figure(), 120.0, 90.0).texts.size());
  for (const char* words : {"Raw and ", "(deg)", "residual (mN", "Knob #3", "stick band"})
    EXPECT_NE(text.text.find(words), std::string::npos) << words << " in " << text.text;
}

TEST_F(FigureFiles, SvgIsXmlWithItsPrintedSizeAndTheLabelsAsTextElements) {
  opt_.formats = {Format::Svg};
  write_figure(sample_figure(), dir_, "fig", opt_);
  const auto svg = knoblab::testing::parse_svg(file_bytes(dir_ / "fig.svg"));
  EXPECT_EQ(svg.root, "svg");
  EXPECT_EQ(svg.root_attributes.at("width"), "120.00mm");
  EXPECT_EQ(svg.root_attributes.at("height"), "90.00mm");
  EXPECT_EQ(svg.root_attributes.at("viewBox"), "0 0 709 531");
  for (const char* label : {"position θ (deg)", "τ (mN·m)", "residual (mN·m)", "Raw and fitted τpos",
                            "Knob #3 — torque against position", "raw τ", "stick band ±Δv", "0"}) {
    EXPECT_NE(std::find(svg.texts.begin(), svg.texts.end(), label), svg.texts.end()) << label;
  }
  // Every piece of text is text: as many <text> elements as the layout has.
  EXPECT_EQ(svg.texts.size(), layout_figure(sample_figure(), 120.0, 90.0).texts.size());
}

TEST_F(FigureFiles, PngHasThePixelsOfItsPrintedSizeAtTheDpiAndSaysSo) {
  for (const int dpi : {150, 300}) {
    opt_.formats = {Format::Png};
    opt_.dpi = dpi;
    write_figure(sample_figure(), dir_, "fig", opt_);
    const auto info = knoblab::testing::png_info(file_bytes(dir_ / "fig.png"));
    EXPECT_EQ(info.width, static_cast<std::uint32_t>(pixels(120.0, dpi)));
    EXPECT_EQ(info.height, static_cast<std::uint32_t>(pixels(90.0, dpi)));
    ASSERT_TRUE(info.dpi.has_value());
    EXPECT_NEAR(*info.dpi, dpi, 0.02);
    // libpng reads it: the chunk we added is a valid one.
    const auto im = knoblab::testing::decode_png(dir_ / "fig.png");
    EXPECT_EQ(im.width, info.width);
  }
}

TEST_F(FigureFiles, CsvHasARowPerPlottedPointUnderColumnsNamedWithUnits) {
  const Figure f = sample_figure();
  opt_.formats = {Format::Png};
  write_figure(f, dir_, "fig", opt_);
  const auto rows = knoblab::testing::csv_rows(file_bytes(dir_ / "fig.csv"));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], (std::vector<std::string>{"panel", "series", "position_deg", "torque_mNm", "torque_lower_mNm"}));
  std::map<std::string, std::size_t> count;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    ASSERT_EQ(rows[r].size(), 5u) << r;
    ++count[rows[r][0] + "/" + rows[r][1]];
  }
  std::size_t points = 0;
  for (const Panel& p : f.panels)
    for (const Series& s : p.series) {
      EXPECT_EQ(count[p.name + "/" + s.name], s.x.size()) << p.name << "/" << s.name;
      points += s.x.size();
    }
  EXPECT_EQ(rows.size() - 1, points);
  // A band row has both edges; a point its y only; a vertical line its x only.
  for (const auto& r : rows) {
    if (r[1] == "band") {
      EXPECT_FALSE(r[4].empty());
    } else if (r[1] == "raw_torque") {
      EXPECT_TRUE(!r[3].empty() && r[4].empty());
    } else if (r[1] == "stick_band_limit") {
      EXPECT_TRUE(!r[2].empty() && r[3].empty());
    }
  }
  EXPECT_EQ(std::stod(rows[1][2]), f.panels[0].series[0].x[0]);
}

TEST_F(FigureFiles, ATextPagesCsvIsItsTable) {
  Figure f;
  f.title = "summary";
  f.text.table = {{"model", "RMS\nmN·m", "p"}, {"base (Eq. 6)", "9.57", "< 1e-12"}, {"a, b", "1.5", "–"}};
  f.text.paragraphs = {"A finding."};
  opt_.formats = {Format::Png};
  opt_.height_mm = 0.0;
  write_figure(f, dir_, "summary", opt_);
  EXPECT_EQ(file_bytes(dir_ / "summary.csv"), "model,RMS mN·m,p\nbase (Eq. 6),9.57,< 1e-12\n\"a, b\",1.5,–\n");
}

TEST_F(FigureFiles, OptionsOutsideTheLimitsWriteNothing) {
  opt_.dpi = 5000;
  EXPECT_THROW(write_figure(sample_figure(), dir_, "fig", opt_), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(FigureFiles, AFileThatCannotBeWrittenIsAnErrorNamingItAndTheOldFileStays) {
  { std::ofstream(dir_ / "fig.png") << "previous"; }
  fs::create_directories(dir_ / "fig.pdf");  // a directory where the PDF should go
  opt_.formats = {Format::Pdf, Format::Png};
  try {
    write_figure(sample_figure(), dir_, "fig", opt_);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "fig.pdf").string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(file_bytes(dir_ / "fig.png"), "previous");
}

}  // namespace
}  // namespace knoblab::fit::plot
