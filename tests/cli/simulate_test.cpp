// knoblab simulate end to end: the CSV it writes, the store it fills.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/sample.hpp"
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
  const std::string effects =
      "hysteresis:presliding_angle_rad=0.002;time_delay:delay_s=0.0005;offset:offset_Nm=0.001";
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
  const auto recorded = model::parse_effect_specs(line), asked = model::parse_effect_specs(effects);
  ASSERT_EQ(recorded.size(), asked.size()) << line;
  for (std::size_t i = 0; i < asked.size(); ++i) {
    EXPECT_EQ(recorded[i].effect, asked[i].effect);
    EXPECT_EQ(recorded[i].params, asked[i].params) << recorded[i].id();
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

// Mistyped effect names get the list to choose from, in both commands.
TEST(Simulate, AnUnknownEffectListsTheKnownOnesInSimulateAndDiscrepancy) {
  const RunResult sim = run_knoblab({"simulate", "--knob", "moderate-detents", "--effects", "cogging:amplitude_Nm=1"});
  EXPECT_EQ(sim.exit_code, 2);
  EXPECT_NE(sim.err.find("unknown effect 'cogging' (known: backlash,"), std::string::npos) << sim.err;
  const RunResult disc = run_knoblab({"discrepancy", "--input", "x.csv", "--effects", "cogging"});
  EXPECT_EQ(disc.exit_code, 2);
  EXPECT_NE(disc.err.find("unknown effect 'cogging' in --effects (known: offset, gravity,"), std::string::npos)
      << disc.err;
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

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The value after `key` in `text` up to the next space or ',' + space: a
// suggestion the error message makes ("--sweep 0,429.7,1,60 (…").
std::string argument_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return "";
  const std::size_t from = at + key.size();
  return text.substr(from, text.find(' ', from) - from);
}

// Eq. 8 has no end: a minute of Table 3's sweep runs at t/6 Hz, and its own
// peak speed 1 rad × 2π·t/6 passes the supervisor's 50 rad/s at t = 47.7 s
// (the knob, a few per cent over the sweep, at 46.5 s). No controller can
// follow it there, so the capture fails — saying where, why and what to
// change — and what was captured is kept, marked incomplete.
TEST(Simulate, AMinuteOfTheTable3SweepStopsOnTheVelocityLimitAndSaysWhereWhyAndWhatToChange) {
  ScratchDir dir;
  const auto csv = dir / "k.csv";
  const auto db_path = dir / "lab.sqlite";
  const RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "60", "--out", csv.string(),
                                   "--db", db_path.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(has(r.err, "stopped at t = 46.5 s")) << r.err;
  EXPECT_TRUE(has(r.err, "safety fault (velocity)")) << r.err;
  EXPECT_TRUE(has(r.err, "passed the 50 rad/s velocity limit")) << r.err;
  EXPECT_TRUE(has(r.err, "reaches the limit itself at t = 47.7 s")) << r.err;
  EXPECT_TRUE(has(r.err, "--seconds 42 or less")) << r.err;
  EXPECT_TRUE(has(r.err, "--sweep 0,429.7,1,60")) << r.err;
  EXPECT_TRUE(has(r.err, "marked incomplete")) << r.err;
  EXPECT_FALSE(has(r.out, "tracking error rms")) << r.out;  // no summary of a failed capture

  // The samples up to the fault, its sample flagged, the file saying why.
  const interchange::Capture c = interchange::read_csv(csv);
  ASSERT_GT(c.size(), 230000u);
  ASSERT_EQ(c.flags.size(), c.size());
  for (std::size_t i = 0; i + 1 < c.size(); ++i)
    ASSERT_EQ(c.flags[i] & (interchange::kAmpEnabled | interchange::kFaultLatched), interchange::kAmpEnabled) << i;
  EXPECT_TRUE(c.flags.back() & interchange::kFaultLatched);
  EXPECT_FALSE(c.flags.back() & interchange::kAmpEnabled);
  EXPECT_NEAR(c.t.back(), 46.5, 0.05);
  ASSERT_TRUE(c.find_metadata("status"));
  EXPECT_EQ(*c.find_metadata("status"), "incomplete");
  ASSERT_TRUE(c.find_metadata("end_reason"));
  EXPECT_EQ(*c.find_metadata("end_reason"), "fault: velocity");

  // The store holds the same samples as an incomplete capture.
  store::Store db = store::Store::open(db_path);
  const auto info = db.capture_info(1);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, "incomplete");
  ASSERT_TRUE(info->end_reason);
  EXPECT_EQ(*info->end_reason, "fault: velocity");
  EXPECT_EQ(info->sample_count, static_cast<std::int64_t>(c.size()));
}

// What the message suggests works: the sweep slowed to stay under 45 rad/s
// runs the whole minute, and so does the default sweep cut at 42 s.
TEST(Simulate, TheChangesTheVelocityFaultSuggestsRunToTheEnd) {
  const RunResult failed = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "60"});
  ASSERT_EQ(failed.exit_code, 1);
  const std::string sweep = argument_after(failed.err, "--sweep ");
  const std::string seconds = argument_after(failed.err, "--seconds ");
  ASSERT_EQ(sweep, "0,429.7,1,60") << failed.err;
  ASSERT_EQ(seconds, "42") << failed.err;
  RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "60", "--sweep", sweep});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "300000 samples, 60.000 s")) << r.out;
  r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", seconds});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

// The high-friction knob (Table 7: 150 mN·m stick band) needs the full
// 180 mN·m torque limit on Table 3's sweep from about 3 Hz (18 s) on; past
// that it falls behind, never fast enough for the velocity limit. That
// capture is not one of the knob: tracking is lost, the capture fails.
TEST(Simulate, AKnobThatNeedsMoreTorqueThanTheLimitLosesTrackingAndTheCaptureFails) {
  ScratchDir dir;
  const RunResult r = run_knoblab({"simulate", "--knob", "high-friction", "--seconds", "40", "--out",
                                   (dir / "k.csv").string()});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(has(r.err, "safety fault (tracking)")) << r.err;
  EXPECT_FALSE(has(r.err, "velocity")) << r.err;
  EXPECT_TRUE(has(r.err, "more than 0.1 rad off the sweep (10 % of its amplitude, at least 0.01 rad) for 20 ms running"))
      << r.err;
  EXPECT_TRUE(has(r.err, "at the 180 mN·m torque limit")) << r.err;
  EXPECT_TRUE(has(r.err, "--seconds ")) << r.err;
  const interchange::Capture c = interchange::read_csv(dir / "k.csv");
  EXPECT_GT(c.t.back(), 15.0);
  EXPECT_LT(c.t.back(), 25.0);
  ASSERT_TRUE(c.find_metadata("end_reason"));
  EXPECT_EQ(*c.find_metadata("end_reason"), "fault: tracking");
  // It pushed at the torque limit before it gave up: those samples say so.
  std::size_t limited = 0;
  for (std::uint32_t f : c.flags) limited += (f & interchange::kTorqueLimited) ? 1 : 0;
  EXPECT_GT(limited, 100u);
}

// A knob against its end stop: the sweep (sin(π·t²/6) rad) asks ±1 rad, the
// stops sit at ±0.5 rad and the knob reaches one at 1 s. Once the sweep is
// 0.1 rad past it (1.13 s) for 20 ms the capture ends.
TEST(Simulate, AKnobHeldByItsEndStopLosesTrackingAsTheSweepPassesTheStop) {
  const RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "2", "--effects",
                                   "endstop:position_rad=0.5,stiffness_Nm_per_rad=10,damping_Nm_s_per_rad=0.01"});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(has(r.err, "safety fault (tracking)")) << r.err;
  const std::string t = argument_after(r.err, "stopped at t = ");
  ASSERT_FALSE(t.empty()) << r.err;
  EXPECT_GT(std::stod(t), 1.13) << r.err;
  EXPECT_LT(std::stod(t), 1.2) << r.err;
  EXPECT_TRUE(has(r.err, "(at the end 0.52 rad, the sweep 0.6")) << r.err;
}

// The CSV carries the loop's flags (here: the amplifier on, every sample),
// which import keeps and fit and inspect read.
TEST(Simulate, TheCsvCarriesTheLoopsFlagsAndFitInspectAndImportReadThem) {
  ScratchDir dir;
  const auto csv = dir / "k.csv";
  RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "6", "--out", csv.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_file(csv);
  EXPECT_TRUE(has(text, "\nt,theta,omega,alpha,torque,command,flags\n")) << text.substr(0, 1200);
  const interchange::Capture c = interchange::read_csv(csv);
  ASSERT_EQ(c.flags.size(), c.size());
  for (std::uint32_t f : c.flags) ASSERT_EQ(f, interchange::kAmpEnabled);
  EXPECT_EQ(c.find_metadata("status"), nullptr);

  r = run_knoblab({"inspect", csv.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "30000 samples")) << r.out;
  EXPECT_TRUE(has(r.out, "flags      amplifier on 30000, fault latched 0, e-stop 0, torque limited 0")) << r.out;
  EXPECT_FALSE(has(r.out, "status")) << r.out;
  r = run_knoblab({"fit", "--input", csv.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(fit::prepare(c).size(), 30000u);  // the amplifier bit excludes nothing
  const auto db_path = dir / "lab.sqlite";
  r = run_knoblab({"import", csv.string(), "--db", db_path.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  store::Store db = store::Store::open(db_path);
  EXPECT_EQ(db.load_samples(1).flags, c.flags);
}

// The samples of a capture cut by a fault can still be fitted: the flags
// column tells the fit to leave the faulted sample out.
TEST(Simulate, AFitOfACutCaptureLeavesTheFaultedSampleOut) {
  ScratchDir dir;
  const auto csv = dir / "k.csv";
  // A sweep at 3.75·t Hz: past 50 rad/s (1 rad × 2π·8 Hz) at 2.1 s.
  RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "4", "--sweep", "0,60,1,4",
                             "--out", csv.string()});
  ASSERT_EQ(r.exit_code, 1) << r.out;
  ASSERT_TRUE(has(r.err, "safety fault (velocity)")) << r.err;
  const interchange::Capture c = interchange::read_csv(csv);
  ASSERT_FALSE(c.flags.empty());
  ASSERT_TRUE(c.flags.back() & interchange::kFaultLatched);
  EXPECT_EQ(fit::prepare(c).size(), c.size() - 1);
  r = run_knoblab({"fit", "--input", csv.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_knoblab({"inspect", csv.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "fault latched 1,")) << r.out;
  EXPECT_TRUE(has(r.out, "status     incomplete: fault: velocity")) << r.out;
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
