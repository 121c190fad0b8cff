// write_discrepancy_report(): the files, their size, that the after-residual
// gets its own, narrower y scale where an effect was found, summary.md's
// table and sentences, and its failures. On the validation data with a
// concealed periodic torque (as discover_test's) and on the clean data.
//
// KNOBLAB_REPORT_EXAMPLE=dir keeps the example report in `dir` to look at.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>

#include <unistd.h>

#include "png_image.hpp"
#include "effect_data.hpp"
#include "knoblab/discovery/report.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::discovery {
namespace {

namespace fs = std::filesystem;

struct Case {
  fit::FitData data;
  DiscrepancyResult r;
};

// 0.8 N·m at 11.3 cycles/rev beside the validation knob's 5 detents/rev.
const Case& with_cogging() {
  static const Case c = [] {
    const model::Detents<double> cogging{0.8, 1.0 / 11.3, 0.5};
    Case k;
    k.data = test_data::with_effect(4, [&](const fit::FitData& d, std::size_t i) {
      return cogging.torque(d.theta[i]);
    });
    // At noise level it cuts the held-out RMS by less than the 20 % bar
    // (discover_test's AConsistentGainUnderTheBarIsTentative); the report
    // is drawn with it reported.
    DiscrepancyOptions o;
    o.min_reported_gain = 0.0;
    k.r = discover(k.data, o);
    return k;
  }();
  return c;
}

const Case& clean() {
  static const Case c = [] {
    Case k;
    k.data = test_data::with_effect(1, nullptr);
    k.r = discover(k.data);
    return k;
  }();
  return c;
}

class DiscrepancyReport : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // The pid too: two builds' tests on one machine must not share a directory.
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("knoblab_discrepancy_report_") + info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::set<std::string> all_files() {
  std::set<std::string> files = {"summary.md"};
  for (const char* stem : {"residual_position", "residual_velocity", "residual_time", "whiteness", "summary"})
    for (const char* ext : {".pdf", ".svg", ".png", ".csv"}) files.insert(std::string(stem) + ext);
  return files;
}

// PNGs only, at 100 dpi: enough for the tests that look at pixels.
ReportOptions png_only() {
  ReportOptions opt;
  opt.figure.formats = {fit::plot::Format::Png};
  opt.figure.dpi = 100;
  return opt;
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

using knoblab::testing::Image;
using knoblab::testing::decode_png;

// The held-out rows' blue (31, 119, 180), with antialiasing slack. (The
// training rows' grey is also the grey of antialiased text.)
bool cloud(const std::array<int, 3>& c) {
  return std::abs(c[0] - 31) <= 14 && std::abs(c[1] - 119) <= 14 && std::abs(c[2] - 180) <= 14;
}

// Standard deviation of the rows of held-out cloud pixels in y ∈ [y0, y1),
// left of the legend column (the plot boxes end at about 72 %).
double cloud_height(const Image& im, std::uint32_t y0, std::uint32_t y1) {
  double n = 0, sum = 0, sq = 0;
  for (std::uint32_t y = y0; y < y1; ++y)
    for (std::uint32_t x = 0; x < im.width * 70 / 100; ++x)
      if (cloud(im.at(x, y))) {
        n += 1;
        sum += y;
        sq += static_cast<double>(y) * y;
      }
  if (n < 100) return 0.0;
  return std::sqrt(sq / n - (sum / n) * (sum / n));
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

TEST_F(DiscrepancyReport, WritesEveryFileAtTheRequestedSize) {
  const Case& c = with_cogging();
  ASSERT_FALSE(c.r.findings.empty()) << to_json(c.r);
  ReportOptions opt;
  opt.title = "validation #4, cogging";
  opt.figure.width_mm = 100.0;
  opt.figure.height_mm = 70.0;
  opt.figure.dpi = 254;
  const auto files = write_discrepancy_report(dir_ / "nested", c.data, c.r, opt);
  std::set<std::string> names;
  for (const fs::path& f : files) {
    names.insert(f.filename().string());
    ASSERT_TRUE(fs::is_regular_file(f)) << f;
    const std::string bytes = read_bytes(f);
    EXPECT_GT(bytes.size(), f.filename() == "summary.csv" ? 100u : 500u) << f;  // summary.csv: its table
    if (f.extension() == ".png") {
      const Image im = decode_png(f);
      EXPECT_EQ(im.width, 1000u) << f;
      EXPECT_EQ(im.height, 700u) << f;
    } else if (f.extension() == ".svg") {
      EXPECT_NE(bytes.find("<svg"), std::string::npos) << f;
      EXPECT_NE(bytes.find("width=\"100.00mm\""), std::string::npos) << f;
    } else if (f.extension() == ".pdf") {
      EXPECT_TRUE(bytes.starts_with("%PDF-")) << f;
    }
  }
  EXPECT_EQ(names, all_files());
  if (const char* keep = std::getenv("KNOBLAB_REPORT_EXAMPLE")) {
    fs::create_directories(keep);
    for (const fs::path& f : files)
      fs::copy_file(f, fs::path(keep) / f.filename(), fs::copy_options::overwrite_existing);
  }
}

// The panel of the named figure.
const fit::plot::Panel& panel(const std::vector<fit::plot::NamedFigure>& figures, std::string_view stem,
                              std::string_view name) {
  for (const auto& f : figures)
    for (const auto& p : f.figure.panels)
      if (f.stem == stem && p.name == name) return p;
  throw std::runtime_error("no panel " + std::string(stem) + "/" + std::string(name));
}

TEST_F(DiscrepancyReport, AfterResidualHasItsOwnNarrowerScaleWhereTheEffectWasFound) {
  // The cogging is concealed (RMS 0.57 beside noise of 1.15 N·m): the
  // held-out RMS falls by about 10 %, and the after panel's scale with it.
  const auto found = discrepancy_figures(with_cogging().data, with_cogging().r);
  for (const char* stem : {"residual_position", "residual_velocity", "residual_time"}) {
    const auto& before = panel(found, stem, "before");
    const auto& after = panel(found, stem, "after");
    EXPECT_LT(after.y_hi, 0.95 * before.y_hi) << stem;
    EXPECT_DOUBLE_EQ(after.y_lo, -after.y_hi);
    // Each scale holds nearly all of its own residual.
    std::size_t inside = 0, all = 0;
    for (const auto& s : after.series)
      if (s.mark == fit::plot::Mark::Dots)
        for (const double y : s.y) inside += std::abs(y) <= after.y_hi ? 1 : 0, ++all;
    EXPECT_GT(inside, 0.99 * static_cast<double>(all)) << stem;
  }
  // Without a finding both panels are the same residual at the same scale.
  const auto none = discrepancy_figures(clean().data, clean().r);
  EXPECT_DOUBLE_EQ(panel(none, "residual_time", "after").y_hi, panel(none, "residual_time", "before").y_hi);
}

TEST_F(DiscrepancyReport, HeldOutRowsAreDrawnInBlueOverTheTrainingRows) {
  const Case& c = with_cogging();
  write_discrepancy_report(dir_, c.data, c.r, png_only());
  const Image im = decode_png(dir_ / "residual_position.png");
  EXPECT_GT(cloud_height(im, 0, im.height / 2), 0.0);
  EXPECT_GT(cloud_height(im, im.height / 2, im.height), 0.0);
  // Drawn order: training rows first, held-out rows over them.
  const auto figures = discrepancy_figures(c.data, c.r);
  const auto& before = panel(figures, "residual_position", "before");
  EXPECT_EQ(before.series[0].name, "training_rows");
  EXPECT_EQ(before.series[1].name, "heldout_rows");
}

TEST_F(DiscrepancyReport, ResidualCsvsHoldEveryPlottedRowInDegrees) {
  const Case& c = with_cogging();
  write_discrepancy_report(dir_, c.data, c.r, png_only());
  const std::string csv = read_bytes(dir_ / "residual_position.csv");
  EXPECT_TRUE(csv.starts_with("panel,series,position_deg,residual_mNm\n")) << csv.substr(0, 80);
  std::size_t rows = 0;
  for (const char ch : csv) rows += ch == '\n' ? 1 : 0;
  // Header; training and held-out rows in each panel; the added torque above; two zero-line points each.
  const std::size_t n = std::min(c.r.trace.size(), ReportOptions{}.max_points);
  EXPECT_EQ(rows, 1 + 2 * n + n + 4);
  EXPECT_NE(read_bytes(dir_ / "summary.csv").find("model,RMS mN·m,held-out RMS mN·m"), std::string::npos);
}

TEST_F(DiscrepancyReport, SummaryHasTheFindingsSentenceAndTheFigures) {
  const Case& c = with_cogging();
  write_discrepancy_report(dir_, c.data, c.r, png_only());
  const std::string md = read_bytes(dir_ / "summary.md");
  EXPECT_NE(md.find(c.r.findings.front().explanation), std::string::npos) << md;
  EXPECT_NE(md.find("periodic_torque"), std::string::npos) << md;
  for (const ModelSummary* m : {&c.r.base, &c.r.final_model}) {
    EXPECT_NE(md.find(fmt("%.4g", m->heldout_rmse_Nm * 1e3)), std::string::npos) << md;
    EXPECT_NE(md.find(fmt("%.4g", m->rmse_Nm * 1e3)), std::string::npos) << md;
    EXPECT_NE(md.find(fmt("%.1f", m->fit_percent)), std::string::npos) << md;
    EXPECT_NE(md.find(fmt("%.0f", m->bic)), std::string::npos) << md;
  }
  EXPECT_GT(c.r.final_model.fit_percent, c.r.base.fit_percent);
  EXPECT_EQ(md.find("Nothing is missing"), std::string::npos);
}

TEST_F(DiscrepancyReport, SummarySaysNothingIsMissingWithoutAFinding) {
  ASSERT_TRUE(clean().r.findings.empty()) << to_json(clean().r);
  write_discrepancy_report(dir_, clean().data, clean().r, png_only());
  const std::string md = read_bytes(dir_ / "summary.md");
  EXPECT_NE(md.find("Nothing is missing"), std::string::npos) << md;
  EXPECT_NE(md.find(fmt("%.4g", clean().r.base.heldout_rmse_Nm * 1e3)), std::string::npos) << md;
}

TEST_F(DiscrepancyReport, SummaryShowsTentativeTermsAsNotReported) {
  // The same cogging under the default 20 % bar: found, not reported.
  const DiscrepancyResult r = discover(with_cogging().data);
  ASSERT_TRUE(r.findings.empty());
  ASSERT_FALSE(r.tentative.empty()) << to_json(r);
  write_discrepancy_report(dir_, with_cogging().data, r, png_only());
  const std::string md = read_bytes(dir_ / "summary.md");
  EXPECT_NE(md.find("Nothing is reported"), std::string::npos) << md;
  EXPECT_NE(md.find(r.tentative.front().explanation), std::string::npos) << md;
  EXPECT_NE(md.find(fmt("%.4g", r.tentative_heldout_rmse_Nm * 1e3)), std::string::npos) << md;
  EXPECT_NE(md.find("final (nothing added)"), std::string::npos) << md;
  EXPECT_EQ(md.find("Nothing is missing"), std::string::npos) << md;
}

TEST_F(DiscrepancyReport, UnwritableDirectoryThrowsWithThePath) {
  fs::create_directories(dir_);
  const fs::path plain = dir_ / "plain_file";
  std::ofstream(plain) << "not a directory";
  const fs::path target = plain / "report";
  try {
    write_discrepancy_report(target, clean().data, clean().r);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
  // A directory where a file should go.
  const fs::path blocker = dir_ / "out" / "whiteness.svg";
  fs::create_directories(blocker);
  try {
    ReportOptions svg = png_only();
    svg.figure.formats = {fit::plot::Format::Svg};
    write_discrepancy_report(dir_ / "out", clean().data, clean().r, svg);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(blocker.string()), std::string::npos) << e.what();
  }
}

TEST_F(DiscrepancyReport, BadInputIsRejected) {
  DiscrepancyResult r = clean().r;
  r.trace.after.pop_back();
  EXPECT_THROW(write_discrepancy_report(dir_, clean().data, r), std::invalid_argument);
  EXPECT_THROW(write_discrepancy_report(dir_, clean().data, DiscrepancyResult{}), std::invalid_argument);
  ReportOptions opt;
  opt.figure.width_mm = 5.0;
  EXPECT_THROW(write_discrepancy_report(dir_, clean().data, clean().r, opt), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_));
}

}  // namespace
}  // namespace knoblab::discovery
