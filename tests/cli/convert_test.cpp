// knoblab convert: real ODrive recordings (../shared/datasets/odrive-cogging)
// to interchange CSV, checked against values computed once with scipy.io; and
// small MAT files built here for unwrapping, segments and bad usage.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "../interchange/mat5_writer.hpp"
#include "../interchange/mat73_writer.hpp"
#include "../interchange/npy_writer.hpp"
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


// ---- static maps: the ODrive cogging maps ---------------------------------

// cogging_measure_final_a_16.npy: 8192 float64 holding currents [A], every
// 16th position measured, the rest 0 (values checked once with numpy).
TEST(Convert, OdriveCoggingMapBecomesAStaticMapWhoseSpectrumShowsTheCoggingHarmonics) {
  REQUIRE_DATASET();
  ScratchDir dir;
  const auto in = odrive_dir() / "coggingmap_0" / "cogging_measure_final_a_16.npy";
  RunResult r = run_knoblab({"convert", in.string(), (dir / "map.csv").string(), "--map-over-rev", "--torque-scale",
                             "0.0551", "--missing", "0", "--knob", "odrive-gimbal"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "static map of 512 of 8192 positions")) << r.out;
  const auto rec = interchange::read_recording(dir / "map.csv");
  ASSERT_TRUE(std::holds_alternative<interchange::StaticMap>(rec));
  const auto& map = std::get<interchange::StaticMap>(rec);
  ASSERT_EQ(map.size(), 512u);
  EXPECT_EQ(map.theta[1], 2 * std::numbers::pi / 8192 * 16);
  EXPECT_EQ(map.theta.back(), 2 * std::numbers::pi / 8192 * 8176);
  const auto [lo, hi] = std::minmax_element(map.torque.begin(), map.torque.end());
  EXPECT_EQ(*lo, -1.686250925064087 * kTorquePerAmp);
  EXPECT_EQ(*hi, 2.194417953491211 * kTorquePerAmp);
  const std::string text = read_file(dir / "map.csv");
  EXPECT_TRUE(text.starts_with("# kind: static-map\n# knob: odrive-gimbal\n")) << text.substr(0, 200);
  EXPECT_TRUE(contains(text, "# missing: 0: 7680 positions not measured, left out\n"));
  EXPECT_FALSE(contains(text, "\nt,") || contains(text, ",t,"));  // no invented time stamps

  // The README's cogging components (7, 12, 14, 28, 36, 84 cycles/rev) are the six strongest.
  r = run_knoblab({"inspect", (dir / "map.csv").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("kind"), "static-map");
  EXPECT_EQ(j.at("points"), 512);
  std::set<int> strongest;
  for (std::size_t i = 0; i < 6; ++i) strongest.insert(j.at("harmonics").at(i).at("cycles_per_rev").get<int>());
  EXPECT_EQ(strongest, (std::set<int>{7, 12, 14, 28, 36, 84}));
  EXPECT_EQ(j.at("harmonics").at(0).at("cycles_per_rev"), 7);
  EXPECT_NEAR(j.at("harmonics").at(0).at("amplitude_Nm").get<double>(), 0.0479056, 1e-6);  // a DFT of the same values: 47.9056 mN·m
  r = run_knoblab({"inspect", (dir / "map.csv").string(), "--csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.starts_with("cycles_per_rev,amplitude_Nm,power\n7,0.0479")) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 9);  // header and the eight strongest
  r = run_knoblab({"inspect", (dir / "map.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "static map of 512 positions")) << r.out;
  EXPECT_TRUE(contains(r.out, "   7:   47.9")) << r.out;
}

TEST(Convert, StaticMapIsRefusedByImportFitAndDiscrepancySayingWhatReadsIt) {
  ScratchDir dir;
  std::vector<double> values(64, 0.0);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::sin(4 * 2 * std::numbers::pi * double(i) / 64);
  write_file(dir / "m.npy", test::npy::f8("(64,)", values));
  RunResult r = run_knoblab({"convert", (dir / "m.npy").string(), (dir / "m.csv").string(), "--map-over-rev"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string why = "m.csv:1: a static map (torque over position, no time stamps), not a recording over time: "
                          "'knoblab inspect' reads it";
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"import", (dir / "m.csv").string(), "--db", (dir / "s.db").string()},
           {"fit", "--input", (dir / "m.csv").string()},
           {"discrepancy", "--input", (dir / "m.csv").string()}}) {
    r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, 1) << args[0];
    EXPECT_TRUE(contains(r.err, why)) << args[0] << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "s.db"));
  r = run_knoblab({"inspect", (dir / "m.csv").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).at("harmonics").at(0).at("cycles_per_rev"), 4);
}

TEST(Convert, MapOptionsMisusedSayWhatIsWrong) {
  ScratchDir dir;
  write_file(dir / "m.npy", test::npy::f8("(8,)", {0, 1, 0, 2, 0, 3, 0, 4}));
  write_file(dir / "m2.npy", test::npy::f8("(2, 4)", {0, 1, 0, 2, 0, 3, 0, 4}));
  const auto in = (dir / "m.npy").string(), out = (dir / "o.csv").string();
  const std::vector<BadUse> cases = {
      {{in, out, "--missing", "0"}, 2, "--missing is for --map-over-rev"},
      {{in, out, "--map-over-rev", "--columns", "t,theta,torque"}, 2, "--columns does not apply to --map-over-rev"},
      {{in, out, "--map-over-rev", "--counts-per-rev", "8192"}, 2, "--counts-per-rev 8192, but m.npy:m holds 8 positions"},
      {{(dir / "m2.npy").string(), out, "--map-over-rev"}, 1,
       "m2.npy:m2 is 2x4 double; --map-over-rev reads a vector of values"},
      {{in, out, "--map-over-rev", "--missing", "0"}, 0, ""},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"convert"};
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const RunResult r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.message << "\n" << r.err;
    EXPECT_TRUE(contains(r.err, c.message)) << r.err;
  }
  const RunResult r = run_knoblab({"convert", in, (dir / "z.csv").string(), "--map-over-rev"});
  EXPECT_TRUE(contains(r.out, "note: 4 of the 8 values are exactly 0; if they mark positions not measured, add --missing 0"))
      << r.out;
}

// ---- the same recording in every array format --------------------------------

// wrapping_matrix() as numpy (rows t, counts, current: shape (3, 7)) and as
// MATLAB v7.3: each converts to the file the MAT v5 original converts to.
TEST(Convert, NpyNpzAndMatV73ConvertToTheSameCsvAsMatV5) {
  ScratchDir dir;
  const std::vector<double> counts = {8000, 8100, 8190, 90, 190, 8150, 8050};
  std::vector<double> row_major(21), col_major;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    row_major[i] = 100.0 + 0.01 * double(i);
    row_major[7 + i] = counts[i];
    row_major[14 + i] = 1.0;
    col_major.insert(col_major.end(), {row_major[i], counts[i], 1.0});
  }
  std::filesystem::create_directories(dir / "v5");
  std::filesystem::create_directories(dir / "v73");
  write_file(dir / "v5" / "data.mat", mat5::Writer().header() + wrapping_matrix());
  {
    test::mat73::File f(dir / "v73" / "data.mat");
    f.numeric("/data", 3, 7, col_major);
  }
  write_file(dir / "data.npy", test::npy::f8("(3, 7)", row_major));
  write_file(dir / "data.npz", test::npy::zip({{"other.npy", test::npy::f8("(1,)", {1}), false},
                                               {"data.npy", test::npy::f8("(3, 7)", row_major), true}}));
  const auto convert = [&](const std::filesystem::path& in, const std::string& out, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"convert", in.string(), (dir / out).string(), "--columns", "t,theta,torque",
                                     "--counts-per-rev", "8192", "--unwrap"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, 0) << in << ": " << r.err;
    return read_file(dir / out);
  };
  // The same file but for the source line, which names file and array.
  const auto with_source = [](std::string text, const std::string& source) {
    const std::size_t at = text.find("# source: ") + 10;
    return text.replace(at, text.find('\n', at) - at, source);
  };
  const std::string v5 = convert(dir / "v5" / "data.mat", "v5.csv");
  EXPECT_TRUE(contains(v5, "# source: data.mat:data\n")) << v5;
  EXPECT_EQ(convert(dir / "v73" / "data.mat", "v73.csv"), v5);
  EXPECT_EQ(convert(dir / "data.npy", "npy.csv"), with_source(v5, "data.npy:data"));  // named after the file
  EXPECT_EQ(convert(dir / "data.npz", "npz.csv", {"--var", "data"}), with_source(v5, "data.npz:data"));
  const RunResult r = run_knoblab({"convert", (dir / "data.npz").string(), (dir / "x.csv").string(), "--columns",
                                   "t,theta,torque"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "holds 2 variables: other (1x1 double), data (3x7 double); choose one with --var")) << r.err;
}

TEST(Convert, Slow2NpyOfTheMatDataConvertsAsTheMatFile) {
  REQUIRE_DATASET();
  ScratchDir dir;
  const auto mat = odrive_dir() / "slow2" / "nocomp_0.mat";
  const auto m = interchange::read_mat_variable(mat, "data");
  std::vector<double> row_major(m.numel());
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < m.cols(); ++c) row_major[r * m.cols() + c] = m.at(r, c);
  write_file(dir / "nocomp_0.npy", test::npy::f8("(3, " + std::to_string(m.cols()) + ")", row_major));
  ASSERT_EQ(run_knoblab(odrive_args(mat, dir / "from_mat.csv")).exit_code, 0);
  const RunResult r = run_knoblab(odrive_args(dir / "nocomp_0.npy", dir / "from_npy.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string from_mat = read_file(dir / "from_mat.csv"), from_npy = read_file(dir / "from_npy.csv");
  EXPECT_TRUE(contains(from_npy, "# source: nocomp_0.npy:nocomp_0\n"));
  from_npy.replace(from_npy.find("nocomp_0.npy:nocomp_0"), 21, "nocomp_0.mat:data");
  EXPECT_EQ(from_npy, from_mat);
}

// ---- other tools' CSV -------------------------------------------------------

TEST(Convert, OtherToolsCsvMapsItsColumnsAndUnitsToSI) {
  ScratchDir dir;
  write_file(dir / "log.csv", "# logger v2\ntime_ms;angle_deg;torque_mNm;counts\n"
                              "1000;0;1.5;0\n1002;0.5;2.5;11\n1004;1.5;-0.5;34\n1006;3;0;68\n");
  RunResult r = run_knoblab({"convert", (dir / "log.csv").string(), (dir / "k.csv").string(), "--columns",
                             "time_ms=t:ms,angle_deg=theta:deg,torque_mNm=torque:mN*m", "--knob", "bench"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "converted log.csv (CSV, delimiter ;): 4 samples over 0.006 s")) << r.out;
  EXPECT_TRUE(contains(r.out, "columns ignored: counts")) << r.out;
  const auto c = interchange::read_csv(dir / "k.csv");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_NEAR(c.t.back(), 0.006, 1e-15);
  EXPECT_EQ(c.theta[3], 3 * (std::numbers::pi / 180));
  EXPECT_EQ(c.torque, (std::vector<double>{1.5 * 1e-3, 2.5 * 1e-3, -0.5 * 1e-3, 0}));
  EXPECT_TRUE(c.omega_derived);
  const std::string text = read_file(dir / "k.csv");
  EXPECT_TRUE(contains(text, "# knob: bench\n# source: log.csv\n# t0_s: 1\n"
                             "# columns: time_ms=t:ms,angle_deg=theta:deg,torque_mNm=torque:mN*m\n"
                             "# ignored_columns: counts\n"))
      << text;

  // Errors name file:line:column, and nothing is written.
  write_file(dir / "bad.csv", "time_ms,angle_deg,torque_mNm\n0,0,0\n1,x,0\n2,0,0\n");
  r = run_knoblab({"convert", (dir / "bad.csv").string(), (dir / "b.csv").string(), "--columns",
                   "time_ms=t:ms,angle_deg=theta:deg,torque_mNm=torque:mN*m"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "bad.csv:3:2: column 'angle_deg': not a number: \"x\"")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "b.csv"));
  for (const auto& [extra, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--columns", "time_ms=t:h,angle_deg=theta,torque_mNm=torque"}, "unit 'h' is not one of t's"},
           {{"--columns", "time_ms=t,angle_deg=theta,torque_mNm=torque", "--torque-scale", "2"},
            "--torque-scale is for arrays; for a CSV give the unit in --columns"},
           {{"--columns", "time_ms=t,angle_deg=theta,torque_mNm=torque", "--delimiter", "|"},
            "--delimiter must be ',', ';' or tab"}}) {
    std::vector<std::string> args = {"convert", (dir / "bad.csv").string(), (dir / "b.csv").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, 2) << message;
    EXPECT_TRUE(contains(r.err, message)) << r.err;
  }
}

TEST(Convert, HelpShowsEveryOptionWithWhatItsValueLooksLike) {
  const RunResult r = run_knoblab({"convert", "--help"});
  ASSERT_EQ(r.exit_code, 0);
  for (const char* hint : {"--columns NAMES|MAPPING", "--var NAME", "--counts-per-rev N", "--theta-scale X",
                           "--torque-scale X", "--segment-time continuous|restart", "--delimiter ,|;|tab",
                           "--missing X|nan", "--knob NAME", "--map-over-rev", "--unwrap"})
    EXPECT_TRUE(contains(r.out, hint)) << hint;
  EXPECT_TRUE(contains(r.out, "\nexamples:\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "--map-over-rev --torque-scale 0.0551 --missing 0\n")) << r.out;
}

}  // namespace
}  // namespace knoblab::test
