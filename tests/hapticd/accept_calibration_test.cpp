// Accepting a calibration: the average of the latest good runs becomes the
// sensors' constants, in the loop, in what later recordings are stored with,
// and in the calibration file hapticd starts from next time.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <thread>

#include "core_harness.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hapticd/calibration_acceptance.hpp"
#include "knoblab/hapticd/calibration_file.hpp"
#include "knoblab/hapticd/control_handler.hpp"
#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/store/store.hpp"
#include "shared_host.hpp"
#include "temp_db.hpp"

namespace knoblab::hapticd {
namespace {

using nlohmann::json;

CalibrationResult run_of(CalibrationKind kind, const capture::SensorCalibration& in_use) {
  CalibrationResult r;
  r.kind = kind;
  r.complete = true;
  r.in_use = in_use;
  r.updated = in_use;
  return r;
}

CalibrationResult accel_run(double C_cal, const capture::SensorCalibration& in_use = {}) {
  CalibrationResult r = run_of(CalibrationKind::AccelGain, in_use);
  r.updated.C_cal = C_cal;
  return r;
}

TEST(AcceptCalibration, TheLatestThreeGoodRunsAreAveragedWithTheirSpread) {
  const std::vector<CalibrationResult> history = {accel_run(900.0), accel_run(1100.0), accel_run(1150.0),
                                                  accel_run(1200.0)};
  auto r = average_runs(history, CalibrationKind::AccelGain, 3, {});
  ASSERT_TRUE(std::holds_alternative<AcceptedCalibration>(r)) << std::get<std::string>(r);
  const AcceptedCalibration& a = std::get<AcceptedCalibration>(r);
  EXPECT_DOUBLE_EQ(a.after.C_cal, 1150.0);  // 900 is older than the latest three
  ASSERT_EQ(a.values.size(), 1u);
  EXPECT_DOUBLE_EQ(a.values[0].sd, 50.0);
  EXPECT_EQ(a.values[0].runs.size(), 3u);
  EXPECT_EQ(a.after.counts_per_rev, a.before.counts_per_rev);  // nothing else changes
}

TEST(AcceptCalibration, FailedStoppedAndStaleRunsDoNotCountAndTheReasonSaysSo) {
  capture::SensorCalibration other;
  other.C_cal = 999.0;
  CalibrationResult failed = accel_run(1150.0);
  failed.error = "a fault latched during the run";
  const std::vector<CalibrationResult> history = {accel_run(1100.0), accel_run(1150.0, other), failed,
                                                  run_of(CalibrationKind::Spatial, {}), accel_run(1200.0)};
  auto r = average_runs(history, CalibrationKind::AccelGain, 3, {});
  ASSERT_TRUE(std::holds_alternative<std::string>(r));
  const std::string& why = std::get<std::string>(r);
  EXPECT_NE(why.find("2 of the 4 ended accel_gain runs qualify"), std::string::npos) << why;
  EXPECT_NE(why.find("1 used constants that have changed since"), std::string::npos) << why;
  // Two are enough when two are asked for.
  EXPECT_TRUE(std::holds_alternative<AcceptedCalibration>(average_runs(history, CalibrationKind::AccelGain, 2, {})));
}

TEST(AcceptCalibration, GravityPhasesAreAveragedOnTheCircle) {
  std::vector<CalibrationResult> history;
  for (const double C : {std::numbers::pi - 0.1, -std::numbers::pi + 0.1, std::numbers::pi}) {
    CalibrationResult r = run_of(CalibrationKind::Gravity, {});
    r.updated.grav_A = 2.0;
    r.updated.grav_C = C;
    r.updated.grav_D = 0.1;
    history.push_back(r);
  }
  auto r = average_runs(history, CalibrationKind::Gravity, 3, {});
  ASSERT_TRUE(std::holds_alternative<AcceptedCalibration>(r));
  const AcceptedCalibration& a = std::get<AcceptedCalibration>(r);
  EXPECT_NEAR(std::abs(std::remainder(a.after.grav_C - std::numbers::pi, 2 * std::numbers::pi)), 0.0, 1e-12);
  EXPECT_NEAR(a.values[1].sd, 0.1, 1e-9);
  EXPECT_DOUBLE_EQ(a.after.grav_A, 2.0);
}

TEST(AcceptCalibration, AVerificationRunChangesNoConstant) {
  const std::vector<CalibrationResult> history(3, run_of(CalibrationKind::Spatial, {}));
  auto r = average_runs(history, CalibrationKind::Spatial, 3, {});
  ASSERT_TRUE(std::holds_alternative<std::string>(r));
  EXPECT_NE(std::get<std::string>(r).find("changes no constant"), std::string::npos);
}

// ---- the calibration file ----

using testing::TempDb;

TEST(CalibrationFile, WhatIsWrittenReadsBackAndATypoIsAnErrorNamingIt) {
  TempDb dir("accept");
  CalibrationFile f;
  f.constants.C_cal = 1148.5;
  f.constants.grav_C = -0.25;
  f.accepted = {{"accel_gain", {{"unix_time", 1.7e9}}}};
  write_calibration_file(dir.dir / "cal.json", f);
  const CalibrationFile back = read_calibration_file(dir.dir / "cal.json");
  EXPECT_TRUE(back.constants == f.constants);
  EXPECT_EQ(back.accepted, f.accepted);

  std::ofstream(dir.dir / "typo.json") << R"({"counts_per_rev": 640000, "torque_Nm_per_V": 0.035,
      "torque_offset_V": 0, "C_call": 1148, "gravity": {"A": 0, "B": 1, "C": 0, "D": 0}})";
  try {
    read_calibration_file(dir.dir / "typo.json");
    FAIL() << "a misspelt key was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("calibration.C_call: unknown key"), std::string::npos) << e.what();
  }
}

// ---- through the daemon: three real runs on the simulated camera ----

// Starts `kind` and waits until the run has ended and been fitted.
void calibrate(ControlHandler& handler, Daemon& d, const char* kind, double sweep_seconds) {
  (void)d.take_finished_calibration();
  control::Request r;
  r.command = control::Command::calibrate;
  r.args = {{"kind", kind}, {"sweep_seconds", sweep_seconds}};
  const control::Reply reply = handler.handle(r);
  ASSERT_TRUE(reply.ok) << reply.error.message;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (d.take_finished_calibration()) return;
  }
  FAIL() << "the calibration did not end";
}

TEST(AcceptCalibrationDaemon, ThreeAccelGainRunsAcceptedChangeTheLoopTheStoreAndTheFile) {
  TempDb dir("accept");
  capture::SensorCalibration truth;
  {
    auto daq = std::make_unique<capture::SimDaq>(testing::free_shaft(), 10000.0);
    truth = daq->calibration();
    DaemonConfig cfg;
    cfg.core.rate_hz = 10000.0;
    cfg.core.calibration = truth;
    cfg.core.calibration.C_cal = 0.8 * truth.C_cal;  // an out-of-date constant
    cfg.db = dir.dir / "lab.sqlite";
    cfg.calibration_file = dir.dir / "calibration.json";
    shared_host::configure(cfg);
    Daemon d(cfg, std::move(daq), std::make_unique<hal::MemoryLines>(false));
    ControlHandler handler(d, {});
    rt::LoopResult timing;
    std::thread loop([&] { timing = d.run(); });

    control::Request accept;
    accept.command = control::Command::accept_calibration;
    accept.args = {{"kind", "accel_gain"}};
    control::Reply early = handler.handle(accept);
    EXPECT_FALSE(early.ok) << "nothing to average yet";
    EXPECT_NE(early.error.message.find("0 of the 0"), std::string::npos) << early.error.message;

    // A run too short to accelerate the shaft is no calibration, and says so.
    calibrate(handler, d, "accel_gain", 0.5);
    ASSERT_TRUE(d.last_calibration());
    EXPECT_NE(d.last_calibration()->error.find("not a usable gain"), std::string::npos) << d.last_calibration()->error;
    for (int i = 0; i < 3; ++i) calibrate(handler, d, "accel_gain", 5.0);  // Table 3's sweep, as long as the thesis ran it
    control::Reply accepted = handler.handle(accept);
    ASSERT_TRUE(accepted.ok) << accepted.error.message;
    const double C_cal = accepted.result["calibration"]["C_cal"].get<double>();
    std::printf("accepted C_cal = %.1f (sd %.1f over %zu runs; truth %.1f, was %.1f)\n", C_cal,
                accepted.result["values"]["C_cal"]["sd"].get<double>(),
                accepted.result["values"]["C_cal"]["runs"].size(), truth.C_cal, 0.8 * truth.C_cal);
    EXPECT_NEAR(C_cal, truth.C_cal, 0.05 * truth.C_cal);
    EXPECT_EQ(accepted.result["repetitions"], 3);
    EXPECT_EQ(accepted.result["saved_to"], (dir.dir / "calibration.json").string());
    EXPECT_DOUBLE_EQ(d.sensor_calibration().C_cal, C_cal);

    control::Request state;
    state.command = control::Command::get_state;
    const json s = handler.handle(state).result;
    EXPECT_DOUBLE_EQ(s["calibration"]["constants"]["C_cal"].get<double>(), C_cal);
    EXPECT_TRUE(s["calibration"]["accepted"].contains("accel_gain"));

    // The runs before were made with other constants: they no longer count.
    control::Reply again = handler.handle(accept);
    EXPECT_FALSE(again.ok);
    EXPECT_NE(again.error.message.find("changed since"), std::string::npos) << again.error.message;

    calibrate(handler, d, "spatial", 0.3);  // a recording made after the accept
    d.stop();
    loop.join();
    shared_host::report_timing(timing);
  }
  // Later recordings are stored with the accepted constants.
  store::Store st = store::Store::open(dir.dir / "lab.sqlite");
  const auto caps = st.list_captures();
  ASSERT_EQ(caps.size(), 5u);
  const double stored = json::parse(caps.back().calibration)["C_cal"].get<double>();
  const CalibrationFile file = read_calibration_file(dir.dir / "calibration.json");
  EXPECT_DOUBLE_EQ(stored, file.constants.C_cal);
  EXPECT_NEAR(file.constants.C_cal, truth.C_cal, 0.05 * truth.C_cal);
  EXPECT_TRUE(file.accepted.contains("accel_gain"));
}

TEST(AcceptCalibrationDaemon, WhenTheFileCannotBeWrittenThePreviousConstantsStay) {
  auto daq = std::make_unique<capture::SimDaq>(testing::free_shaft(), 10000.0);
  DaemonConfig cfg;
  cfg.core.rate_hz = 10000.0;
  cfg.core.calibration = daq->calibration();
  cfg.calibration_file = "/nonexistent-dir/calibration.json";
  shared_host::configure(cfg);
  const double before = cfg.core.calibration.C_cal;
  Daemon d(cfg, std::move(daq), std::make_unique<hal::MemoryLines>(false));
  ControlHandler handler(d, {});
  rt::LoopResult timing;
  std::thread loop([&] { timing = d.run(); });
  calibrate(handler, d, "accel_gain", 5.0);
  control::Request accept;
  accept.command = control::Command::accept_calibration;
  accept.args = {{"kind", "accel_gain"}, {"repetitions", 1}};
  const control::Reply r = handler.handle(accept);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.message.find("cannot save"), std::string::npos) << r.error.message;
  EXPECT_DOUBLE_EQ(d.sensor_calibration().C_cal, before);
  d.stop();
  loop.join();
  shared_host::report_timing(timing);
}

}  // namespace
}  // namespace knoblab::hapticd
