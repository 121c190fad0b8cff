// write_report(): the sixteen files (PDF, SVG, PNG and CSV of four figures),
// what the figures show, and its failures. The fit is made by hand from a
// known Eq. 6 model, so the test does not depend on the fitter.
//
// KNOBLAB_REPORT_EXAMPLE=dir keeps one example report in `dir` for a person
// to look at.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "figure_checks.hpp"
#include "png_image.hpp"
#include "knoblab/fit/plot/legend.hpp"
#include "knoblab/fit/report.hpp"

namespace knoblab::fit {
namespace {

namespace fs = std::filesystem;

// Eq. 6 parameters in fit order (SI): M_acc, C−, B−, C+, B+, A, P, S.
constexpr std::array<double, model::kThesisParamCount> kParams = {
    1.0e-5, 2.0e-3, 2.0e-4, 2.5e-3, 1.6e-4, 5.0e-3, 1.0 / 12.0, 0.4};

struct Case {
  FitResult r;
  FitData d;
  Prediction p;
};

// A swept sine θ(t) = 2·sin(2π(f0·t + k·t²/2)), 0.1 → 1.5 Hz over 10 s at
// 500 Hz, with torque from the known model plus white noise.
Case make_case(double noise_Nm = 0.5e-3, unsigned seed = 1, bool detents = true,
               std::size_t n = 5000) {
  Case c;
  std::array<double, model::kThesisParamCount> params = kParams;
  if (!detents) params[model::kA_pos] = 0.0;
  const auto m = model::ThesisModel<double>::from_params(params.data());

  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_Nm);
  const double rate = 500.0, f0 = 0.1, k = 0.14, amp = 2.0;
  const double two_pi = 2.0 * std::numbers::pi;
  c.d.rate_hz = rate;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / rate;
    const double phi = two_pi * (f0 * t + 0.5 * k * t * t);
    const double dphi = two_pi * (f0 + k * t), ddphi = two_pi * k;
    const double theta = amp * std::sin(phi);
    const double omega = amp * std::cos(phi) * dphi;
    const double alpha = -amp * std::sin(phi) * dphi * dphi + amp * std::cos(phi) * ddphi;
    c.d.t.push_back(t);
    c.d.theta.push_back(theta);
    c.d.omega.push_back(omega);
    c.d.alpha.push_back(alpha);

    const model::TorqueParts<double> parts = m.parts({theta, omega, alpha});
    c.d.torque.push_back(parts.total() + noise(rng));
    c.p.acc.push_back(parts.acc);
    c.p.vel.push_back(parts.vel);
    c.p.pos.push_back(parts.pos);
    c.p.tau.push_back(parts.total());
    // A band that grows with speed, like a real one; the observation band
    // adds the noise.
    const double half = 0.02e-3 + 0.004e-3 * std::abs(omega);
    c.p.curve_half.push_back(half);
    c.p.observation_half.push_back(std::hypot(half, 1.96 * noise_Nm));
  }

  c.r.model = ModelKind::Thesis6;
  c.r.names.assign(model::kThesisParamNames.begin(), model::kThesisParamNames.end());
  c.r.params.assign(params.begin(), params.end());
  c.r.fitted.assign(params.size(), true);
  c.r.detents = detents;
  if (!detents) {
    c.r.fitted[model::kA_pos] = c.r.fitted[model::kP_pos] = c.r.fitted[model::kS_pos] = false;
  }
  c.r.stick = StickBand{0.3, 2.0e-3, 2.5e-3, 40};
  c.r.samples = n;
  c.r.rmse_Nm = noise_Nm;
  c.r.fit_percent = 97.0;
  return c;
}

class ReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("knoblab_report_") + info->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

const std::vector<std::string> kFiles = {
    "torque_position.pdf", "torque_position.svg", "torque_position.png", "torque_position.csv",
    "torque_velocity.pdf", "torque_velocity.svg", "torque_velocity.png", "torque_velocity.csv",
    "torque_time.pdf",     "torque_time.svg",     "torque_time.png",     "torque_time.csv",
    "ci_torque.pdf",       "ci_torque.svg",       "ci_torque.png",       "ci_torque.csv"};

// PNGs only, at 200 dpi (a cloud's 0.4 mm dots 3 px wide): what the tests
// that look at pixels need.
ReportOptions png_only(std::size_t max_points = 20000) {
  ReportOptions opt;
  opt.figure.formats = {plot::Format::Png};
  opt.figure.dpi = 200;
  opt.max_points = max_points;
  return opt;
}

using knoblab::testing::file_bytes;
std::string read_bytes(const fs::path& file) { return file_bytes(file); }
std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& png) {
  const auto info = knoblab::testing::png_info(png);
  return {info.width, info.height};
}

using knoblab::testing::Image;
using knoblab::testing::decode_png;

bool dark(const std::array<int, 3>& c) { return c[0] < 100 && c[1] < 100 && c[2] < 100; }
// The raw clouds' light gray (190, 190, 190), with some antialiasing slack.
bool cloud_gray(const std::array<int, 3>& c) {
  return c[0] == c[1] && c[1] == c[2] && c[0] >= 180 && c[0] <= 200;
}
std::size_t count(const Image& im, bool (*pred)(const std::array<int, 3>&)) {
  std::size_t n = 0;
  for (std::uint32_t y = 0; y < im.height; ++y)
    for (std::uint32_t x = 0; x < im.width; ++x) n += pred(im.at(x, y)) ? 1 : 0;
  return n;
}

TEST_F(ReportTest, WritesTheSixteenFilesAndCreatesTheDirectory) {
  const Case c = make_case();
  const fs::path dir = dir_ / "nested" / "report";
  ReportOptions opt;
  opt.title = "Knob #3 (swept sine)";
  const auto files = write_report(c.r, c.d, c.p, dir, opt);
  ASSERT_EQ(files.size(), kFiles.size());
  std::set<std::string> names;
  for (const fs::path& f : files) {
    EXPECT_EQ(f.parent_path(), dir);
    EXPECT_TRUE(fs::is_regular_file(f)) << f;
    EXPECT_GT(fs::file_size(f), 1000u) << f;
    names.insert(f.filename().string());
  }
  EXPECT_EQ(names, std::set<std::string>(kFiles.begin(), kFiles.end()));

  if (const char* keep = std::getenv("KNOBLAB_REPORT_EXAMPLE")) {
    fs::create_directories(keep);
    for (const fs::path& f : files)
      fs::copy_file(f, fs::path(keep) / f.filename(), fs::copy_options::overwrite_existing);
  }
}

TEST_F(ReportTest, FilesHaveTheRequestedSizeInEveryFormat) {
  const Case c = make_case();
  ReportOptions opt;
  opt.figure.width_mm = 100.0;
  opt.figure.height_mm = 64.0;
  opt.figure.dpi = 254;
  for (const fs::path& f : write_report(c.r, c.d, c.p, dir_, opt)) {
    const std::string bytes = read_bytes(f);
    if (f.extension() == ".png") {
      const auto [w, h] = png_size(bytes);
      EXPECT_EQ(w, 1000u) << f;
      EXPECT_EQ(h, 640u) << f;
    } else if (f.extension() == ".svg") {
      const auto svg = knoblab::testing::parse_svg(bytes);
      EXPECT_EQ(svg.root_attributes.at("width"), "100.00mm") << f;
      EXPECT_EQ(svg.root_attributes.at("height"), "64.00mm") << f;
    } else if (f.extension() == ".pdf") {
      EXPECT_TRUE(knoblab::testing::pdf_contains(bytes, "/MediaBox [ 0 0 283 181 ]")) << f;
    }
  }
}

TEST_F(ReportTest, PlotsAreWhiteWithBlackAxesAndAGrayCloud) {
  const Case c = make_case();
  write_report(c.r, c.d, c.p, dir_, png_only());
  for (const char* name : {"torque_position.png", "torque_velocity.png", "torque_time.png"}) {
    const Image im = decode_png(dir_ / name);
    ASSERT_EQ(im.width, 1260u);  // 160 mm at 200 dpi
    // White background.
    const std::uint32_t r = im.width - 1, b = im.height - 1;
    for (const auto& [x, y] : {std::pair{0u, 0u}, std::pair{r, 0u}, std::pair{0u, b}, std::pair{r, b}})
      EXPECT_EQ(im.at(x, y), (std::array<int, 3>{255, 255, 255})) << name;
    // Stacked plot boxes (two or three): some column is dark over about half
    // the height or more (the left frames of the panels).
    std::uint32_t best = 0;
    for (std::uint32_t x = 0; x < im.width; ++x) {
      std::uint32_t rows = 0;
      for (std::uint32_t y = 0; y < im.height; ++y) rows += dark(im.at(x, y)) ? 1 : 0;
      best = std::max(best, rows);
    }
    EXPECT_GT(best, im.height * 45 / 100) << name;
    // The raw cloud covers a real area of the page.
    EXPECT_GT(count(im, cloud_gray), im.width * im.height / 100) << name;
  }
}

TEST_F(ReportTest, RawCloudsAreThinnedToMaxPoints) {
  const Case c = make_case();  // 5000 samples
  write_report(c.r, c.d, c.p, dir_ / "few", png_only(100));
  write_report(c.r, c.d, c.p, dir_ / "all", png_only());
  const auto rows = [&](const char* dir) {
    std::size_t n = 0;
    for (const auto& row : knoblab::testing::csv_rows(file_bytes(dir_ / dir / "torque_time.csv")))
      n += row.size() > 1 && row[1] == "raw_torque" ? 1 : 0;
    return n;
  };
  EXPECT_EQ(rows("few"), 100u);
  EXPECT_EQ(rows("all"), 5000u);
  const std::size_t gray_few = count(decode_png(dir_ / "few" / "torque_position.png"), cloud_gray);
  const std::size_t gray_all = count(decode_png(dir_ / "all" / "torque_position.png"), cloud_gray);
  EXPECT_LT(gray_few * 5, gray_all);
}

TEST_F(ReportTest, OutputFollowsTheData) {
  // Same input, same bytes (no time stamps): so a difference below is the data.
  const Case a = make_case(0.5e-3, 1);
  const Case b = make_case(0.5e-3, 2);
  write_report(a.r, a.d, a.p, dir_ / "a1", png_only());
  write_report(a.r, a.d, a.p, dir_ / "a2", png_only());
  write_report(b.r, b.d, b.p, dir_ / "b", png_only());
  for (const char* name : {"torque_position.png", "torque_velocity.png", "torque_time.png"}) {
    const std::string a1 = read_bytes(dir_ / "a1" / name);
    EXPECT_EQ(a1, read_bytes(dir_ / "a2" / name)) << name;
    EXPECT_NE(a1, read_bytes(dir_ / "b" / name)) << name;
  }
}

// The residual panels' shading: the fit's band (60, 100, 190) and the
// observation band (200, 218, 242), with antialiasing slack.
bool curve_fill(const std::array<int, 3>& c) {
  return std::abs(c[0] - 60) <= 12 && std::abs(c[1] - 100) <= 12 && std::abs(c[2] - 190) <= 12;
}
bool obs_fill(const std::array<int, 3>& c) {
  return std::abs(c[0] - 200) <= 6 && std::abs(c[1] - 218) <= 6 && std::abs(c[2] - 242) <= 6;
}

TEST_F(ReportTest, BandsAreShadedWhereTheyCanBeSeen) {
  // The fit's band is 0.02–0.05 mN·m against a torque of tens: on the torque
  // panels thinner than a line. The residual panels show both bands shaded.
  const Case c = make_case();
  write_report(c.r, c.d, c.p, dir_ / "clean", png_only());
  // Transients the fit left out (3% of samples, 40 mN·m) must not squash them.
  Case spiky = make_case();
  for (std::size_t i = 0; i < spiky.d.size(); i += 33) spiky.d.torque[i] += 40e-3;
  write_report(spiky.r, spiky.d, spiky.p, dir_ / "spiky", png_only());
  for (const char* name : {"torque_position.png", "torque_velocity.png", "torque_time.png"}) {
    const Image clean = decode_png(dir_ / "clean" / name);
    const Image with_spikes = decode_png(dir_ / "spiky" / name);
    const std::size_t page = std::size_t{clean.width} * clean.height;
    EXPECT_GT(count(clean, curve_fill), page / 2000) << name;
    EXPECT_GT(count(clean, obs_fill), page / 200) << name;
    EXPECT_GT(2 * count(with_spikes, obs_fill), count(clean, obs_fill)) << name;
  }
}

TEST_F(ReportTest, KnobWithoutDetentsStillGetsPositionPlots) {
  const Case c = make_case(0.5e-3, 1, /*detents=*/false);
  const auto files = write_report(c.r, c.d, c.p, dir_, png_only());
  ASSERT_EQ(files.size(), 8u);
  const Image im = decode_png(dir_ / "torque_position.png");
  EXPECT_GT(count(im, cloud_gray), im.width * im.height / 100);
}

TEST_F(ReportTest, WorksWithoutAnObservationBand) {
  Case c = make_case();
  c.p.observation_half.clear();
  EXPECT_EQ(write_report(c.r, c.d, c.p, dir_, png_only()).size(), 8u);
}

TEST_F(ReportTest, NonFiniteBandValuesAreLeftOut) {
  // A failed covariance gives NaN bands; the rest of the report still draws.
  Case c = make_case(0.5e-3, 1, true, 2000);
  for (std::size_t i = 0; i < c.p.curve_half.size(); i += 7)
    c.p.curve_half[i] = std::numeric_limits<double>::quiet_NaN();
  c.p.observation_half.assign(c.p.observation_half.size(),
                              std::numeric_limits<double>::infinity());
  ASSERT_EQ(write_report(c.r, c.d, c.p, dir_, png_only()).size(), 8u);
  const Image im = decode_png(dir_ / "torque_position.png");
  EXPECT_GT(count(im, cloud_gray), im.width * im.height / 100);
}

TEST_F(ReportTest, ConcurrentCallsAreSerialized) {
  const Case c = make_case(0.5e-3, 1, true, 1500);
  std::vector<std::size_t> written(3, 0);
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < written.size(); ++k) {
    threads.emplace_back([&, k] {
      written[k] = write_report(c.r, c.d, c.p, dir_ / std::to_string(k), png_only()).size();
    });
  }
  for (auto& t : threads) t.join();
  for (std::size_t k = 0; k < written.size(); ++k) {
    EXPECT_EQ(written[k], 8u);  // a PNG and a CSV of each figure
    const std::string png = read_bytes(dir_ / std::to_string(k) / "torque_position.png");
    EXPECT_EQ(png_size(png).first, 1260u);
  }
}

TEST_F(ReportTest, UncreatableDirectoryThrowsWithThePath) {
  const Case c = make_case(0.5e-3, 1, true, 500);
  fs::create_directories(dir_);
  const fs::path plain = dir_ / "plain_file";
  std::ofstream(plain) << "not a directory";
  const fs::path target = plain / "report";
  try {
    write_report(c.r, c.d, c.p, target);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
}

TEST_F(ReportTest, UnwritableFileThrowsWithThePath) {
  // A directory where a file should go: PLplot must not get to prompt or exit.
  const Case c = make_case(0.5e-3, 1, true, 500);
  const fs::path blocker = dir_ / "torque_velocity.svg";
  fs::create_directories(blocker);
  ReportOptions opt = png_only();
  opt.figure.formats = {plot::Format::Svg, plot::Format::Png};
  try {
    write_report(c.r, c.d, c.p, dir_, opt);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(blocker.string()), std::string::npos) << e.what();
  }
  // The files before it were written, and PLplot still works afterwards.
  EXPECT_TRUE(fs::is_regular_file(dir_ / "torque_position.png"));
  fs::remove_all(blocker);
  EXPECT_EQ(write_report(c.r, c.d, c.p, dir_, opt).size(), 12u);
}

TEST_F(ReportTest, MismatchedSizesAreRejected) {
  const Case good = make_case(0.5e-3, 1, true, 500);
  {
    Case c = good;
    c.p.tau.pop_back();
    EXPECT_THROW(write_report(c.r, c.d, c.p, dir_), std::invalid_argument);
  }
  {
    Case c = good;
    c.p.curve_half.push_back(0.0);
    EXPECT_THROW(write_report(c.r, c.d, c.p, dir_), std::invalid_argument);
  }
  {
    Case c = good;
    c.p.observation_half.resize(10);
    EXPECT_THROW(write_report(c.r, c.d, c.p, dir_), std::invalid_argument);
  }
  {
    Case c = good;
    c.d.torque.pop_back();
    EXPECT_THROW(write_report(c.r, c.d, c.p, dir_), std::invalid_argument);
  }
  {
    Case c = good;
    c.d = FitData{};
    c.p = Prediction{};
    EXPECT_THROW(write_report(c.r, c.d, c.p, dir_), std::invalid_argument);
  }
  ReportOptions opt;
  opt.max_points = 0;
  EXPECT_THROW(write_report(good.r, good.d, good.p, dir_, opt), std::invalid_argument);
  opt = {};
  opt.figure.width_mm = 0.0;
  EXPECT_THROW(write_report(good.r, good.d, good.p, dir_, opt), std::invalid_argument);
  opt = {};
  opt.figure.formats.clear();
  EXPECT_THROW(write_report(good.r, good.d, good.p, dir_, opt), std::invalid_argument);
  // Nothing was written for rejected input.
  EXPECT_FALSE(fs::exists(dir_));
}


// The rows of a report CSV for one panel and series.
std::vector<std::vector<std::string>> csv_series(const fs::path& csv, const std::string& panel,
                                                 const std::string& series) {
  std::vector<std::vector<std::string>> out;
  for (const auto& row : knoblab::testing::csv_rows(file_bytes(csv)))
    if (row.size() > 1 && row[0] == panel && row[1] == series) out.push_back(row);
  return out;
}

TEST_F(ReportTest, EachFiguresCsvHoldsThePlottedPointsInDegreesAndMilliNewtonMetres) {
  const Case c = make_case();  // 5000 samples, θ ±2 rad
  write_report(c.r, c.d, c.p, dir_, png_only(700));
  const auto header = knoblab::testing::csv_rows(file_bytes(dir_ / "torque_position.csv")).front();
  EXPECT_EQ(header, (std::vector<std::string>{"panel", "series", "position_deg", "torque_mNm", "torque_lower_mNm"}));
  EXPECT_EQ(knoblab::testing::csv_rows(file_bytes(dir_ / "torque_velocity.csv")).front()[2], "velocity_deg_per_s");
  EXPECT_EQ(knoblab::testing::csv_rows(file_bytes(dir_ / "torque_time.csv")).front()[2], "time_s");
  // The raw cloud, thinned to max_points, in degrees and mN·m.
  const auto raw = csv_series(dir_ / "torque_position.csv", "total", "raw_torque");
  ASSERT_EQ(raw.size(), 700u);
  double most_deg = 0.0, most_mNm = 0.0;
  for (const auto& row : raw) {
    most_deg = std::max(most_deg, std::abs(std::stod(row[2])));
    most_mNm = std::max(most_mNm, std::abs(std::stod(row[3])));
  }
  EXPECT_NEAR(most_deg, 2.0 * 180.0 / std::numbers::pi, 1.0);
  EXPECT_GT(most_mNm, 5.0);  // the detents alone are 5 mN·m
  // The first raw row is the first sample.
  EXPECT_NEAR(std::stod(raw.front()[3]), 1e3 * c.d.torque[0], 1e-6);
  EXPECT_EQ(csv_series(dir_ / "torque_time.csv", "residual", "residual").size(), 700u);
  // The stick band's limits at ±Δv in deg/s, where the velocity figure draws them.
  const auto limits = csv_series(dir_ / "torque_velocity.csv", "velocity_part", "stick_band_limit");
  ASSERT_EQ(limits.size(), 2u);
  EXPECT_NEAR(std::stod(limits[1][2]), 0.3 * 180.0 / std::numbers::pi, 1e-6);
}

TEST_F(ReportTest, LegendsListTheObservationBandOnlyWhenThereIsOne) {
  Case c = make_case(0.5e-3, 1, true, 1000);
  const auto has_obs = [](const std::vector<plot::NamedFigure>& figures) {
    std::size_t panels = 0;
    for (const auto& f : figures)
      for (const auto& p : f.figure.panels)
        for (const auto& e : plot::legend_entries(p)) panels += e.label == "95% observation band" ? 1 : 0;
    return panels;
  };
  EXPECT_EQ(has_obs(report_figures(c.r, c.d, c.p)), 5u);  // two part panels, three residual panels
  c.p.observation_half.clear();
  EXPECT_EQ(has_obs(report_figures(c.r, c.d, c.p)), 0u);
}

TEST_F(ReportTest, RawDataIsDrawnFirstUnderTheModelWithOnlyBandsBelowIt) {
  const Case c = make_case(0.5e-3, 1, true, 1000);
  for (const auto& f : report_figures(c.r, c.d, c.p)) {
    if (f.stem == "ci_torque") continue;
    for (const auto& p : f.figure.panels) {
      std::size_t k = 0;
      while (k < p.series.size() && p.series[k].mark == plot::Mark::Fill) ++k;
      ASSERT_LT(k, p.series.size());
      const auto& first = p.series[k];
      EXPECT_TRUE(first.name.starts_with("raw") || first.name == "residual") << f.stem << "/" << p.name;
      EXPECT_EQ(first.mark, plot::Mark::Dots);
      EXPECT_EQ(first.color.r, plot::palette::kRaw.r);  // light grey
    }
  }
}

}  // namespace
}  // namespace knoblab::fit
