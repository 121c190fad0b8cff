// knoblab simulate end to end: the CSV it writes, the store it fills.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>

#include "knoblab/interchange/csv.hpp"
#include "knoblab/model/periodogram.hpp"
#include "knoblab/sim/library_effects.hpp"
#include "knoblab/sim/presets.hpp"
#include "knoblab/store/store.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

// Drops the "# …" lines: the samples alone.
std::string data_lines(const std::string& csv) {
  std::string out;
  std::size_t pos = 0;
  while (pos < csv.size()) {
    std::size_t end = csv.find('\n', pos);
    if (end == std::string::npos) end = csv.size();
    if (csv[pos] != '#') out += csv.substr(pos, end - pos + 1);
    pos = end + 1;
  }
  return out;
}

struct DetentCase {
  const char* knob;
  double cycles_per_rev;
};

class SimulatedDetents : public ::testing::TestWithParam<DetentCase> {};

// Acceptance: the capture's torque-versus-position spectrum peaks at the
// knob's detent count (Table 5), within the thesis' 3 % (Table 8).
TEST_P(SimulatedDetents, SpectrumPeaksAtTheDetentCount) {
  ScratchDir dir;
  const auto csv = dir / "k.csv";
  const RunResult r = run_knoblab({"simulate", "--knob", GetParam().knob, "--seconds", "6", "--rate",
                                   "5000", "--out", csv.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const interchange::Capture c = interchange::read_csv(csv);  // valid interchange CSV
  ASSERT_EQ(c.size(), 30000u);
  EXPECT_FALSE(c.omega_derived);
  EXPECT_FALSE(c.alpha_derived);
  EXPECT_TRUE(c.has_command);
  EXPECT_NEAR(c.t.back(), 29999.0 / 5000.0, 1e-12);
  const auto pg = model::angular_periodogram(c.theta, c.torque, 1.0, 64.0, 0.05);
  EXPECT_NEAR(pg.peak.frequency, GetParam().cycles_per_rev, 0.03 * GetParam().cycles_per_rev);
}

INSTANTIATE_TEST_SUITE_P(Thesis, SimulatedDetents,
                         ::testing::Values(DetentCase{"moderate-detents", 12.0},
                                           DetentCase{"subtle-detents", 30.0}),
                         [](const auto& p) {
                           std::string name = p.param.knob;
                           std::erase(name, '-');
                           return name;
                         });

TEST(Simulate, SameSeedSameCaptureOtherSeedOtherNoise) {
  ScratchDir dir;
  auto sim = [&](const char* seed, const char* name) {
    const RunResult r = run_knoblab({"simulate", "--knob", "subtle-detents", "--seconds", "0.5",
                                     "--seed", seed, "--out", (dir / name).string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return data_lines(read_file(dir / name));
  };
  const std::string a = sim("7", "a.csv"), b = sim("7", "b.csv"), c = sim("8", "c.csv");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

// Every effect asked for is in the capture's description, the ones folded
// into the knob (hysteresis) as well as the rig's (delay) and torques (offset),
// and it acts: the play-free, undelayed knob gives other samples.
TEST(Simulate, TheEffectsAskedForAreInTheCaptureAndAct) {
  ScratchDir dir;
  const std::string effects = "hysteresis:presliding=0.002;time_delay:delay=0.0005;offset:tau0=0.001";
  RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "0.5", "--effects", effects,
                             "--out", (dir / "with.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "0.5", "--out", (dir / "without.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string with = read_file(dir / "with.csv");
  const std::string key = "# effects: ";
  const std::size_t at = with.find(key);
  ASSERT_NE(at, std::string::npos) << with.substr(0, 800);
  const std::string line = with.substr(at + key.size(), with.find('\n', at) - at - key.size());
  const auto recorded = sim::parse_effect_specs(line), asked = sim::parse_effect_specs(effects);
  ASSERT_EQ(recorded.size(), asked.size()) << line;
  for (std::size_t i = 0; i < asked.size(); ++i) {
    EXPECT_EQ(recorded[i].id, asked[i].id);
    EXPECT_EQ(recorded[i].params, asked[i].params) << recorded[i].id;
  }
  EXPECT_NE(data_lines(with), data_lines(read_file(dir / "without.csv")));
}

TEST(Simulate, TracksTheSweptSineAndStaysInsideTheSensorRange) {
  ScratchDir dir;
  const RunResult r = run_knoblab({"simulate", "--knob", "high-inertia", "--seconds", "3", "--out",
                                   (dir / "k.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const interchange::Capture c = interchange::read_csv(dir / "k.csv");
  double max_err = 0, max_tau = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    // Table 3 spatial sweep: θ_ref = sin(π·t²/3) (a = 0, b = 1.5, c = 1, d = 3).
    const double ref = std::sin(std::acos(-1.0) / 1.5 * (1.5 * c.t[i] / 3.0) * (1.5 * c.t[i] / 3.0));
    max_err = std::max(max_err, std::abs(ref - c.theta[i]));
    max_tau = std::max(max_tau, std::abs(c.torque[i]));
  }
  EXPECT_LT(max_err, 0.02);  // rad: the PID follows the stimulus
  EXPECT_GT(max_tau, 0.005);  // the knob pushed back
  EXPECT_LE(max_tau, 0.180);  // the sensor saturates at ±180 mN·m
}

TEST(Simulate, ParamsFileGivesTheSameKnobAsThePreset) {
  ScratchDir dir;
  const sim::KnobParams k = *sim::presets::knob("moderate-detents");
  char json[1024];
  std::snprintf(json, sizeof json,
                "{\"model\": \"thesis6\", \"params\": {\"M_acc\": %.17g, \"C_vel_neg\": %.17g, "
                "\"B_vel_neg\": %.17g, \"C_vel_pos\": %.17g, \"B_vel_pos\": %.17g, \"A_pos\": %.17g, "
                "\"P_pos\": %.17g, \"S_pos\": %.17g}, \"stick\": {\"dv\": %.17g, \"D_neg\": %.17g, "
                "\"D_pos\": %.17g}}",
                k.inertia.M, k.friction.C_neg, k.friction.B_neg, k.friction.C_pos, k.friction.B_pos,
                k.detents.A, k.detents.P, k.detents.S, k.stick.dv, k.stick.D_neg, k.stick.D_pos);
  write_file(dir / "knob.json", json);
  const std::vector<std::string> common = {"--seconds", "0.5", "--seed", "3"};
  auto args = [&](std::vector<std::string> a) {
    a.insert(a.end(), common.begin(), common.end());
    return a;
  };
  ASSERT_EQ(run_knoblab(args({"simulate", "--knob", "moderate-detents", "--out", (dir / "a.csv").string()})).exit_code, 0);
  ASSERT_EQ(run_knoblab(args({"simulate", "--params", (dir / "knob.json").string(), "--out", (dir / "b.csv").string()})).exit_code, 0);
  EXPECT_EQ(data_lines(read_file(dir / "a.csv")), data_lines(read_file(dir / "b.csv")));

  write_file(dir / "bad.json", "{\"params\": {\"M_acc\": 1e-5, \"Q\": 2}}");
  RunResult r = run_knoblab({"simulate", "--params", (dir / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown parameter 'Q'"), std::string::npos) << r.err;
  write_file(dir / "bad.json", "{\"params\": {\"M_acc\": -1e-5}}");
  r = run_knoblab({"simulate", "--params", (dir / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not physical"), std::string::npos) << r.err;
  write_file(dir / "bad.json", "{\"params\": ");
  r = run_knoblab({"simulate", "--params", (dir / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not valid JSON"), std::string::npos) << r.err;
}

// The loop closes: what fit writes, simulate reads, as it is written.
TEST(Simulate, ParamsTakesAFitsResultJsonAndItsRenderModelAsWritten) {
  ScratchDir dir;
  const auto csv = (dir / "a.csv").string();
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "3", "--out", csv}).exit_code, 0);
  const auto fit_json = (dir / "fit.json").string(), render = (dir / "render.json").string();
  const RunResult fit = run_knoblab({"fit", "--input", csv, "--json", fit_json, "--render-model", render});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  ASSERT_NE(read_file(fit_json).find("\"stick\""), std::string::npos);  // with its samples count
  for (const auto& file : {fit_json, render}) {
    const RunResult r = run_knoblab({"simulate", "--params", file, "--seconds", "1", "--out", (dir / "b.csv").string()});
    EXPECT_EQ(r.exit_code, 0) << file << ": " << r.err;
  }

  write_file(dir / "bad.json", "{\"model\": \"render4\", \"params\": {\"M_acc\": 1e-5, \"C_vel_pos\": 1e-3}}");
  const RunResult r = run_knoblab({"simulate", "--params", (dir / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown parameter 'C_vel_pos' (known: M_acc, B_vel, A_pos, P_pos, S_pos, dv, D_neg, D_pos)"),
            std::string::npos)
      << r.err;
}

// 60 s at 10 kHz through the loop into the store: every sample arrives.
TEST(Simulate, SixtySecondsAtTenKilohertzLoseNothing) {
  ScratchDir dir;
  const auto db_path = dir / "lab.sqlite";
  // A sweep slow enough for a minute: 1.5 Hz at 60 s, 9.4 rad/s at most.
  const RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "60", "--rate",
                                   "10000", "--sweep", "0,90,1,60", "--db", db_path.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  store::Store db = store::Store::open(db_path);
  const auto info = db.capture_info(1);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, "complete");
  EXPECT_EQ(info->sample_count, 600000);
  const interchange::Capture c = db.load_samples(1);
  ASSERT_EQ(c.size(), 600000u);
  for (std::size_t i = 0; i < c.size(); ++i)
    ASSERT_EQ(c.t[i], static_cast<double>(i) * (1.0 / 10000.0)) << "sample " << i;
  EXPECT_EQ(db.integrity_check(), "ok");
}

TEST(Simulate, ACaptureCutBySafetySaysWhyAndExitsNonZero) {
  // Table 3's sweep, run for a minute, reaches 7.8 Hz × 1 rad at 46.5 s: the
  // knob then passes the 50 rad/s velocity limit and the supervisor stops it.
  const RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "60", "--rate", "10000"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("safety fault (velocity)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("velocity limit 50 rad/s"), std::string::npos) << r.err;
}

TEST(ImportExport, RoundTripKeepsEverySampleAndTheDescription) {
  ScratchDir dir;
  const auto db = (dir / "lab.sqlite").string();
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "subtle-detents", "--seconds", "0.4", "--mode", "tripod",
                         "--out", (dir / "a.csv").string()}).exit_code, 0);
  RunResult r = run_knoblab({"import", (dir / "a.csv").string(), "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2000 samples as capture 1"), std::string::npos) << r.out;
  r = run_knoblab({"export", "1", "--db", db, "--out", (dir / "b.csv").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Equal values (sqlite stores -0.0 as 0.0, which compares equal).
  const interchange::Capture a = interchange::read_csv(dir / "a.csv");
  const interchange::Capture b = interchange::read_csv(dir / "b.csv");
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_EQ(a.omega, b.omega);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.torque, b.torque);
  EXPECT_EQ(a.command, b.command);
  store::Store s = store::Store::open(db);
  const auto info = s.capture_info(1);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->knob, "subtle-detents");
  EXPECT_EQ(info->mode, "tripod");
  EXPECT_NE(info->calibration.find("C_cal"), std::string::npos);
  EXPECT_NE(info->stimulus.find("swept_sine"), std::string::npos);
  r = run_knoblab({"export", "9", "--db", db, "--out", (dir / "c.csv").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no capture 9"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.csv"));
}

}  // namespace
}  // namespace knoblab::test
