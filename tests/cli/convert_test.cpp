// knoblab convert: real ODrive recordings (../shared/datasets/odrive-cogging)
// to interchange CSV, checked against values computed once with scipy.io; and
// small MAT files built here for unwrapping, segments and bad usage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "../interchange/mat5_writer.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/mat5.hpp"
#include "odrive_data.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

constexpr double kCountsToRad = 2 * std::numbers::pi / 8192;
constexpr double kTorquePerAmp = 0.0551;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(Convert, OdriveSlowRotationMatchesScipy) {
  REQUIRE_DATASET();
  ScratchDir dir;
  const auto in = odrive_dir() / "slow2" / "nocomp_0.mat";
  const RunResult r = run_knoblab(odrive_args(in, dir / "n0.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "4306 samples")) << r.out;

  const auto c = interchange::read_csv(dir / "n0.csv");
  // scipy.io.loadmat(...)["data"]: shape (3, 4306), t from 9.5367431640625e-07 to 9.998166561126709.
  ASSERT_EQ(c.size(), 4306u);
  EXPECT_EQ(c.t.front(), 0.0);
  EXPECT_DOUBLE_EQ(c.t.back(), 9.998166561126709 - 9.5367431640625e-07);
  EXPECT_DOUBLE_EQ(c.theta.front(), 0.7508174180984497 * kCountsToRad);
  EXPECT_DOUBLE_EQ(c.torque.front(), 0.6406428813934326 * kTorquePerAmp);
  EXPECT_DOUBLE_EQ(c.torque.back(), 0.020515117794275284 * kTorquePerAmp);
  // Every sample: the same arithmetic on what the reader gives, exactly (shortest round trip).
  const auto m = interchange::read_mat_variable(in, "data");
  for (std::size_t i = 0; i < c.size(); ++i) {
    ASSERT_EQ(c.t[i], m.at(0, i) - m.at(0, 0)) << i;
    ASSERT_EQ(c.theta[i], m.at(1, i) * (2 * std::numbers::pi / 8192)) << i;
    ASSERT_EQ(c.torque[i], m.at(2, i) * kTorquePerAmp) << i;
  }
  for (const char* line : {"# knob: odrive-gimbal\n", "# source: nocomp_0.mat:data\n", "# t0_s: 9.5367431640625e-07\n",
                           "# counts_per_rev: 8192\n", "# torque_scale: 0.0551\n", "# unwrapped_jumps: 0\n"})
    EXPECT_TRUE(contains(read_file(dir / "n0.csv"), line)) << line;
}

// nocomp_1 does not wrap: it starts at 8158 counts (≈ -34, where the previous
// run ended), swings back one revolution through 0 to -1568 under position
// control, settles near 0 and then turns forward to 8155. So theta spans
// 7.46 rad, and --unwrap rightly changes nothing (largest step 287 counts).
TEST(Convert, OdriveRunWithAResetMoveStaysContinuous) {
  REQUIRE_DATASET();
  ScratchDir dir;
  const RunResult r = run_knoblab(odrive_args(odrive_dir() / "slow2" / "nocomp_1.mat", dir / "n1.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "0 position jump(s) unwrapped")) << r.out;
  const auto c = interchange::read_csv(dir / "n1.csv");
  ASSERT_EQ(c.size(), 4267u);
  const auto [lo, hi] = std::minmax_element(c.theta.begin(), c.theta.end());
  EXPECT_NEAR(*hi - *lo, 7.459496996391618, 1e-12);
  double step = 0;
  for (std::size_t i = 1; i < c.size(); ++i) step = std::max(step, std::abs(c.theta[i] - c.theta[i - 1]));
  EXPECT_NEAR(step, 0.2200064008125362, 1e-12);
  EXPECT_DOUBLE_EQ(c.t.back(), 9.999473094940186);
}

// accel_tests: a 4x50 cell array, row 1 the setpoint; each segment's clock
// starts again at ~0, so they are joined with --segment-time restart.
TEST(Convert, OdriveCurrentStepsJoinTheirSegments) {
  REQUIRE_DATASET();
  ScratchDir dir;
  const auto in = odrive_dir() / "accel_tests" / "spinup_4_nocomp.mat";
  std::vector<std::string> args = {"convert", in.string(), (dir / "s4.csv").string(), "--columns", "-,t,theta,torque",
                                   "--counts-per-rev", "8192", "--torque-scale", "0.0551"};
  RunResult r = run_knoblab(args);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "spinup_4_nocomp.mat:data: segment 2 (cell column 2) starts at t = ")) << r.err;
  EXPECT_TRUE(contains(r.err, "use --segment-time restart")) << r.err;

  args.insert(args.end(), {"--segment-time", "restart"});
  r = run_knoblab(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto c = interchange::read_csv(dir / "s4.csv");
  // scipy: sum of data[1, j].size over the 50 segments; joined time with a
  // median in-segment interval (0.0007541179656982422 s) between segments.
  EXPECT_EQ(c.size(), 65476u);
  EXPECT_NEAR(c.t.back(), 50.05588459968567, 1e-9);
  EXPECT_DOUBLE_EQ(c.torque.front(), -0.05883543938398361 * kTorquePerAmp);
  EXPECT_DOUBLE_EQ(c.theta.back(), 5118841.0 * kCountsToRad);
  EXPECT_TRUE(contains(read_file(dir / "s4.csv"), "# segments: 50, clock restarting"));
}

// ---- small files built here --------------------------------------------------

std::filesystem::path write_mat(const ScratchDir& dir, const std::string& name, const std::string& elements) {
  const auto path = dir / name;
  write_file(path, mat5::Writer().header() + elements);
  return path;
}

// Rows t, position (counts, wrapping modulo 8192), current.
std::string wrapping_matrix() {
  const std::vector<double> counts = {8000, 8100, 8190, 90, 190, 8150, 8050};  // forward, wrap, back again
  std::vector<double> v;
  for (std::size_t i = 0; i < counts.size(); ++i) v.insert(v.end(), {100.0 + 0.01 * double(i), counts[i], 1.0});
  return mat5::Writer().doubles("data", 3, static_cast<std::int32_t>(counts.size()), v);
}

TEST(Convert, UnwrapUndoesModuloJumps) {
  ScratchDir dir;
  const auto in = write_mat(dir, "w.mat", wrapping_matrix());
  const RunResult r = run_knoblab({"convert", in.string(), (dir / "w.csv").string(), "--columns", "t,theta,torque",
                                   "--counts-per-rev", "8192", "--unwrap"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "2 position jump(s) unwrapped")) << r.out;
  const auto c = interchange::read_csv(dir / "w.csv");
  const std::vector<double> expect = {8000, 8100, 8190, 8282, 8382, 8150, 8050};
  for (std::size_t i = 0; i < expect.size(); ++i) EXPECT_DOUBLE_EQ(c.theta[i], expect[i] * kCountsToRad) << i;
  EXPECT_NEAR(c.t.back(), 0.06, 1e-12);
  EXPECT_TRUE(contains(read_file(dir / "w.csv"), "# t0_s: 100\n"));
}

TEST(Convert, ColumnsAsChannelsAndPlainScale) {
  ScratchDir dir;
  // 4x3: columns are t, theta, torque (column-major values).
  const auto in = write_mat(dir, "c.mat", mat5::Writer().doubles("x", 4, 3, {0, 1, 2, 3, 0, 2, 4, 6, 5, 5, 5, 5}));
  const RunResult r = run_knoblab({"convert", in.string(), (dir / "c.csv").string(), "--columns", "t, theta, torque",
                                   "--theta-scale", "0.5", "--torque-scale", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto c = interchange::read_csv(dir / "c.csv");
  EXPECT_EQ(c.theta, (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(c.torque, (std::vector<double>{10, 10, 10, 10}));
  EXPECT_EQ(c.omega, (std::vector<double>{1, 1, 1, 1}));  // derived from theta
  EXPECT_TRUE(c.omega_derived);  // not written: the file says what was measured
  EXPECT_TRUE(c.alpha_derived);
}

TEST(Convert, SegmentsJoinDroppingARepeatedBoundarySample) {
  ScratchDir dir;
  const mat5::Writer w;
  const auto row = [&](std::vector<double> v) { return w.doubles("", 1, static_cast<std::int32_t>(v.size()), v); };
  // Rows t, theta, torque; segment 2 repeats segment 1's last sample.
  const auto in = write_mat(dir, "s.mat", w.cell("data", 3, 2, {row({0, 1, 2}), row({0, 1, 2}), row({7, 7, 7}),
                                                                row({2, 3, 4}), row({2, 3, 4}), row({8, 8, 8})}));
  RunResult r = run_knoblab({"convert", in.string(), (dir / "s.csv").string(), "--columns", "t,theta,torque"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto c = interchange::read_csv(dir / "s.csv");
  EXPECT_EQ(c.t, (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(c.torque, (std::vector<double>{7, 7, 7, 8, 8}));

  const auto uneven = write_mat(dir, "u.mat", w.cell("data", 3, 2, {row({0, 1, 2}), row({0, 1, 2}), row({7, 7, 7}),
                                                                    row({3, 4, 5}), row({3, 4}), row({8, 8, 8})}));
  r = run_knoblab({"convert", uneven.string(), (dir / "u.csv").string(), "--columns", "t,theta,torque"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "u.mat:data: segment 2 (cell column 2): row 2 has 2 values, the t row 1 has 3")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "u.csv"));
}

struct BadUse {
  std::vector<std::string> extra;  // after IN OUT
  int exit_code;
  std::string message;
};

TEST(Convert, BadUsageSaysWhatIsWrong) {
  ScratchDir dir;
  const auto in = write_mat(dir, "w.mat", wrapping_matrix());
  const auto text = dir / "not.mat";
  write_file(text, "t,theta,torque\n0,0,0\n");
  const std::vector<BadUse> cases = {
      {{"--columns", "t,theta,torque,command"}, 1, "w.mat:data is 3x7 double: neither its rows nor its columns match the 4 names in --columns"},
      {{"--columns", "t,theta,torque", "--var", "position"}, 1, "no variable 'position'; the file holds data (3x7 double)"},
      {{"--columns", "t,angle,torque"}, 2, "--columns: unknown channel 'angle'"},
      {{"--columns", "t,theta,-"}, 2, "--columns must name t, theta and torque"},
      {{"--columns", "t,theta,theta"}, 2, "--columns: 'theta' given twice"},
      {{"--columns", "t,theta,torque", "--unwrap"}, 2, "--unwrap needs --counts-per-rev"},
      {{"--columns", "t,theta,torque", "--counts-per-rev", "8192", "--theta-scale", "2"}, 2, "not both"},
      {{"--columns", "t,theta,torque", "--counts-per-rev", "0"}, 2, "--counts-per-rev must be positive"},
      {{"--columns", "t,theta,torque", "--segment-time", "restart"}, 2, "--segment-time is for cell arrays"},
      {{}, 2, "'convert' needs --columns"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"convert", in.string(), (dir / "o.csv").string()};
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const RunResult r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.message << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.message)) << r.err;
  }
  RunResult r = run_knoblab({"convert", text.string(), (dir / "o.csv").string(), "--columns", "t,theta,torque"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "not.mat: not a MAT v5 file")) << r.err;
  r = run_knoblab({"convert", (dir / "missing.mat").string(), (dir / "o.csv").string(), "--columns", "t,theta,torque"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "missing.mat: cannot read")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o.csv"));
}

}  // namespace
}  // namespace knoblab::test
