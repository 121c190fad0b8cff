// Calibrate mode: the controller's reference, and the runs end to end on the
// simulated camera through HapticCore and the daemon. The fits themselves
// (Table 4, Eq. 12, Eq. 2) on synthetic data: tests/fit/calibration_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <numbers>
#include <type_traits>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hapticd/calibration_controller.hpp"
#include "knoblab/hapticd/core.hpp"
#include "knoblab/hapticd/control_handler.hpp"
#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/store/store.hpp"
#include "knoblab/sim/presets.hpp"
#include "core_harness.hpp"
#include "shared_host.hpp"

namespace knoblab::hapticd {
namespace {

constexpr double kPi = std::numbers::pi;

static_assert(std::is_trivially_copyable_v<CalibrationController>);
static_assert(std::is_trivially_copyable_v<CalibrationData>);
static_assert(std::is_trivially_copyable_v<CoreCommand>);

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }

TEST(CalibrationController, GravityReferenceIsOneRevolutionEachWayAndReturns) {
  CalibrationConfig cc;
  cc.kind = CalibrationKind::Gravity;
  cc.gravity_seconds = 4.0;
  cc.gravity_ramp_seconds = 0.5;
  const CalibrationController c(cc);
  EXPECT_EQ(c.cycles(), static_cast<std::int64_t>(2 * (4.0 + 1.5) * 10000));
  const double w0 = 2 * kPi / 4.0;
  EXPECT_NEAR(c.reference(2.0).omega, w0, 1e-12);
  EXPECT_TRUE(c.reference(2.0).fit);
  EXPECT_FALSE(c.reference(0.7).fit);  // settling after the ramp
  EXPECT_NEAR(c.reference(1.0 + 4.0 - 1e-9).theta - c.reference(1.0).theta, 2 * kPi, 1e-6);
  EXPECT_NEAR(c.reference(5.5 + 3.0).omega, -w0, 1e-12);
  EXPECT_TRUE(c.reference(5.5 + 3.0).ccw);
  EXPECT_NEAR(c.reference(11.0).theta, 0.0, 1e-9);  // back where it started
  EXPECT_NEAR(c.reference(11.0).omega, 0.0, 1e-9);
  // Continuity of θ across the ramp boundaries and the turn-around.
  for (double t : {0.5, 1.0, 5.0, 5.5, 6.0, 6.5, 10.5}) {
    EXPECT_NEAR(c.reference(t - 1e-7).theta, c.reference(t + 1e-7).theta, 1e-5) << t;
    EXPECT_NEAR(c.reference(t - 1e-7).omega, c.reference(t + 1e-7).omega, 1e-4) << t;
  }
}

// ---- end to end: SimDaq + HapticCore ----

struct CalRun {
  CalibrationResult result;
  std::int64_t calibrate_cycles = 0;
  double max_abs_command_V = 0.0;
  bool ended_idle = false;
};

CalRun run_calibration(capture::SimDaq& daq, CalibrationConfig cc, const capture::SensorCalibration& in_use) {
  CoreConfig core_cfg;
  core_cfg.rate_hz = 10000.0;
  core_cfg.calibration = in_use;
  HapticCore core(core_cfg);
  cc.rate_hz = core_cfg.rate_hz;
  cc.calibration = in_use;
  cc.torque_per_volt = core_cfg.limits.torque_per_volt;
  CoreCommand start;
  start.kind = CoreCommand::StartCalibration;
  start.calibration = CalibrationController(cc);
  EXPECT_TRUE(core.post(start));
  EXPECT_EQ(core.calibrations_finished(), 0u);
  CalRun r;
  const std::int64_t n = start.calibration.cycles();
  for (std::int64_t i = 0; i < n + 100; ++i) {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    LoopRecord rec;
    EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
    core.cycle(in, {}, out, rec);
    EXPECT_EQ(daq.write(out), capture::IoStatus::ok);
    if (rec.mode == Mode::Calibrate) ++r.calibrate_cycles;
    r.max_abs_command_V = std::max(r.max_abs_command_V, std::abs(rec.sample.command));
  }
  r.ended_idle = core.state().mode == Mode::Idle;
  EXPECT_EQ(core.calibrations_finished(), 1u);
  r.result = evaluate(core.last_calibration());
  return r;
}

void print(const char* what, const fit::Table4& t) {
  std::printf("%s: theta %.3g/%.3g rad, omega %.3g/%.3g rad/s, alpha %.3g/%.3g rad/s^2, torque %.3g/%.3g N.m "
              "(mean/SD of commanded - measured)\n",
              what, t.theta.mean, t.theta.sd, t.omega.mean, t.omega.sd, t.alpha.mean, t.alpha.sd, t.torque.mean,
              t.torque.sd);
}

TEST(CalibrationRun, GravityOnATiltedTripodRecoversTheTrueCompensation) {
  sim::PlantConfig p;
  p.load = sim::Load::Free;
  // The unloaded camera still turns its gripper and sensor flange: with the
  // bare 1e-6 kg·m² rotor of Eq. 3 the thesis PID (Kd = 1 V·s/rad) is unstable.
  p.motor.extra_inertia = sim::presets::kHapticKnobInertia;
  p.mounting = sim::CameraOrientation::tripod(0.6, 0.9);  // 34° from vertical, rolled
  p.initial_angle = 0.25;
  capture::SimDaq daq(p, 10000.0);
  const sim::AccelCalibration truth = daq.plant().accel_calibration();
  capture::SensorCalibration in_use = daq.calibration();
  in_use.grav_A = in_use.grav_C = in_use.grav_D = 0.0;  // uncalibrated
  CalibrationConfig cc;
  cc.kind = CalibrationKind::Gravity;
  cc.gravity_seconds = 4.0;  // the thesis takes ~16 s a revolution; shorter for the test
  cc.gravity_ramp_seconds = 0.5;
  const CalRun r = run_calibration(daq, cc, in_use);
  ASSERT_TRUE(r.result.ok()) << r.result.error;
  ASSERT_TRUE(r.result.gravity);
  EXPECT_TRUE(r.ended_idle);
  EXPECT_EQ(r.calibrate_cycles, 110000);
  const fit::GravityFit& g = *r.result.gravity;
  std::printf("gravity: fit A=%.3f+-%.3f C=%.4f+-%.4f D=%.3f+-%.3f (95%%; cw A=%.3f C=%.4f, ccw A=%.3f C=%.4f); "
              "truth A=%.3f C=%.4f D=%.3f\n",
              g.A, g.A_ci95, g.C, g.C_ci95, g.D, g.D_ci95, g.cw.A, g.cw.C, g.ccw.A, g.ccw.C, truth.A, truth.C,
              truth.D);
  ASSERT_GT(truth.A, 100.0);
  EXPECT_NEAR(g.A, truth.A, 0.02 * truth.A);
  EXPECT_NEAR(wrap(g.C - truth.C), 0.0, 0.02);
  EXPECT_NEAR(g.D, truth.D, 0.02 * truth.A);
  EXPECT_NEAR(r.result.updated.grav_A, g.A, 0.0);
  // The intervals: A and D from two directions (1 dof), C from the regressions.
  EXPECT_NEAR(g.A_ci95, 12.7062 * g.A_se, 1e-4 * g.A_se + 1e-12);
  EXPECT_NEAR(g.D_ci95, 12.7062 * g.D_se, 1e-4 * g.D_se + 1e-12);
  EXPECT_GT(g.C_se, 0.0);
  EXPECT_GT(g.C_dof, 1000.0);
  EXPECT_NEAR(g.C_ci95, 1.96 * g.C_se, 0.01 * g.C_se);
}

using testing::free_shaft;

TEST(CalibrationRun, SpatialOnAFreeShaftTracksLikeTable4) {
  capture::SimDaq daq(free_shaft(), 10000.0);
  CalibrationConfig cc;
  cc.kind = CalibrationKind::Spatial;
  const CalRun r = run_calibration(daq, cc, daq.calibration());
  ASSERT_TRUE(r.result.ok()) << r.result.error;
  EXPECT_EQ(r.calibrate_cycles, 50000);  // 5 s, thesis §2.2.1
  EXPECT_GT(r.max_abs_command_V, 0.01);  // it did move
  const fit::Table4& t = r.result.table4;
  print("spatial (Load::Free)", t);
  // Table 4: θ 1.2 ± 3.2 mrad, ω 1.6 ± 24 mrad/s, α 0.66 ± 0.42 rad/s².
  EXPECT_EQ(t.theta.n, 50000);
  EXPECT_LT(std::abs(t.theta.mean), 0.005);
  EXPECT_LT(t.theta.sd, 0.01);
  EXPECT_LT(std::abs(t.omega.mean), 0.01);
  EXPECT_LT(t.omega.sd, 0.1);
  // The simulated ADXL202 is noisier (σ 8.7 rad/s²) than Table 4's α row.
  EXPECT_LT(std::abs(t.alpha.mean), 1.0);
  EXPECT_LT(t.alpha.sd, 15.0);
  EXPECT_EQ(t.torque.n, 0);
  EXPECT_NEAR(t.theta.mean_ci95, 1.96 * t.theta.sd / std::sqrt(50000.0), 1e-3 * t.theta.sd);
  EXPECT_FALSE(r.result.accel);
}

TEST(CalibrationRun, AccelGainRecoversCcalFromTheSpatialSweep) {
  capture::SimDaq daq(free_shaft(), 10000.0);
  const double true_C = daq.plant().accel_calibration().C_cal;
  capture::SensorCalibration in_use = daq.calibration();
  in_use.C_cal = 1000.0;  // wrong on purpose: the fit works on raw volts
  CalibrationConfig cc;
  cc.kind = CalibrationKind::AccelGain;
  const CalRun r = run_calibration(daq, cc, in_use);
  ASSERT_TRUE(r.result.ok()) << r.result.error;
  ASSERT_TRUE(r.result.accel);
  const fit::AccelGainFit& a = *r.result.accel;
  std::printf("accel_gain: C_cal=%.1f +- %.1f (95%%; se %.1f, truth %.1f), residual %.2f rad/s^2, gravity seen A=%.1f "
              "(truth %.1f)\n",
              a.C_cal, a.C_cal_ci95, a.C_cal_se, true_C, a.residual_sd, a.grav_A, daq.plant().accel_calibration().A);
  EXPECT_NEAR(a.C_cal, true_C, 0.03 * true_C);
  EXPECT_LT(a.C_cal_se, 0.03 * true_C);
  EXPECT_DOUBLE_EQ(r.result.updated.C_cal, a.C_cal);
  EXPECT_EQ(a.dof, a.n - 4);  // C_cal and the three gravity terms
  EXPECT_NEAR(a.C_cal_ci95, 1.96 * a.C_cal_se, 0.01 * a.C_cal_se);
}

TEST(CalibrationRun, TorqueWithTheGripperAnchored) {
  sim::PlantConfig p;
  p.load = sim::Load::Anchored;
  capture::SimDaq daq(p, 10000.0);
  CalibrationConfig cc;
  cc.kind = CalibrationKind::Torque;
  const CalRun r = run_calibration(daq, cc, daq.calibration());
  ASSERT_TRUE(r.result.ok()) << r.result.error;
  const fit::Table4& t = r.result.table4;
  print("torque (Load::Anchored)", t);
  EXPECT_GT(t.torque.n, 49000);
  EXPECT_GT(r.max_abs_command_V, 5.0);  // it did push
  // Table 4: τ 1.0 ± 1.8 mN·m. Same order: a few mN·m at most.
  EXPECT_LT(std::abs(t.torque.mean), 0.005);
  EXPECT_LT(t.torque.sd, 0.010);
}

TEST(CalibrationRun, StopEndsARunEarlyAndItReportsIncomplete) {
  sim::PlantConfig p;
  p.load = sim::Load::Free;
  // The unloaded camera still turns its gripper and sensor flange: with the
  // bare 1e-6 kg·m² rotor of Eq. 3 the thesis PID (Kd = 1 V·s/rad) is unstable.
  p.motor.extra_inertia = sim::presets::kHapticKnobInertia;
  capture::SimDaq daq(p, 10000.0);
  CoreConfig core_cfg;
  core_cfg.calibration = daq.calibration();
  HapticCore core(core_cfg);
  CalibrationConfig cc;
  cc.calibration = core_cfg.calibration;
  CoreCommand start;
  start.kind = CoreCommand::StartCalibration;
  start.calibration = CalibrationController(cc);
  ASSERT_TRUE(core.post(start));
  for (int i = 0; i < 2000; ++i) {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    LoopRecord rec;
    EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
    core.cycle(in, {}, out, rec);
    EXPECT_EQ(daq.write(out), capture::IoStatus::ok);
    if (i == 999) {
      EXPECT_EQ(core.state().mode, Mode::Calibrate);
      EXPECT_TRUE(out.amp_enable);
      CoreCommand stop;
      stop.kind = CoreCommand::StopCapture;
      ASSERT_TRUE(core.post(stop));
    }
  }
  EXPECT_EQ(core.state().mode, Mode::Idle);
  ASSERT_EQ(core.calibrations_finished(), 1u);
  const CalibrationResult res = evaluate(core.last_calibration());
  EXPECT_FALSE(res.complete);
  EXPECT_FALSE(res.ok());
  EXPECT_EQ(res.cycles, 1001);  // the cycle the stop arrived in is the run's last
}

TEST(CalibrationRun, AnEmptyControllerDoesNotEnterCalibrate) {
  CoreConfig core_cfg;
  HapticCore core(core_cfg);
  CoreCommand start;
  start.kind = CoreCommand::StartCalibration;  // default controller: no run
  ASSERT_TRUE(core.post(start));
  capture::DaqOutputs out;
  LoopRecord rec;
  core.cycle({}, {}, out, rec);
  EXPECT_EQ(core.state().mode, Mode::Idle);
  EXPECT_FALSE(out.amp_enable);
}

// ---- through the daemon: the paced realtime loop, the writer, the store ----

TEST(CalibrationDaemon, StartCalibrationRunsRecordsAndPublishesItsResultOnce) {
  std::string tmpl = "/tmp/knoblab-calib-XXXXXX";
  const std::filesystem::path dir = mkdtemp(tmpl.data());
  {
    auto daq = std::make_unique<capture::SimDaq>(free_shaft(), 10000.0);
    DaemonConfig cfg;
    cfg.core.rate_hz = 10000.0;
    cfg.core.calibration = daq->calibration();
    cfg.db = dir / "lab.sqlite";
    shared_host::configure(cfg);
    Daemon d(cfg, std::move(daq), std::make_unique<hal::MemoryLines>(false));
    rt::LoopResult timing;
    std::thread loop([&] { timing = d.run(); });
    EXPECT_FALSE(d.last_calibration());
    CalibrationConfig cc;
    cc.kind = CalibrationKind::Spatial;
    cc.sweep_seconds = 0.5;
    double seconds = 0.0;
    std::string why;
    ASSERT_TRUE(d.start_calibration(cc, seconds, why)) << why;
    EXPECT_DOUBLE_EQ(seconds, 0.5);
    std::optional<CalibrationResult> got;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!got && std::chrono::steady_clock::now() < end) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      got = d.take_finished_calibration();
    }
    EXPECT_FALSE(d.take_finished_calibration());  // once only
    ASSERT_TRUE(got);
    EXPECT_TRUE(got->ok()) << got->error;
    EXPECT_EQ(got->kind, CalibrationKind::Spatial);
    EXPECT_EQ(got->cycles, 5000);
    EXPECT_EQ(got->table4.theta.n, 5000);
    ASSERT_TRUE(d.last_calibration());
    EXPECT_EQ(d.core().state().mode, Mode::Idle);
    // A second run may start now that the first has ended.
    CalibrationConfig bad;
    bad.sweep_seconds = -1.0;
    EXPECT_FALSE(d.start_calibration(bad, seconds, why));
    EXPECT_NE(why.find("duration"), std::string::npos) << why;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    d.stop();
    loop.join();
    shared_host::report_timing(timing);
  }
  store::Store s = store::Store::open(dir / "lab.sqlite");
  const auto caps = s.list_captures();
  ASSERT_EQ(caps.size(), 1u);
  EXPECT_NE(caps[0].metadata.find("spatial"), std::string::npos) << caps[0].metadata;
  std::filesystem::remove_all(dir);
}

TEST(CalibrationDaemon, CalibrateTakesItsDurationsFromTheRequest) {
  auto daq = std::make_unique<capture::SimDaq>(free_shaft(), 10000.0);
  DaemonConfig cfg;
  cfg.core.rate_hz = 10000.0;
  cfg.core.calibration = daq->calibration();
  shared_host::configure(cfg);
  Daemon d(cfg, std::move(daq), std::make_unique<hal::MemoryLines>(false));
  ControlHandler handler(d, {});
  control::Request r;
  r.command = control::Command::calibrate;
  r.args = {{"kind", "spatial"}, {"sweep_seconds", 0.7}, {"pid", {{"Kp", 150.0}}}};
  control::Reply reply = handler.handle(r);
  ASSERT_TRUE(reply.ok) << reply.error.message;
  EXPECT_DOUBLE_EQ(reply.result["seconds"].get<double>(), 0.7);
  EXPECT_EQ(reply.result["samples"], 7000);

  // A second daemon: the first one's loop never ran, so its run is still queued.
  Daemon d2(cfg, std::make_unique<capture::SimDaq>(free_shaft(), 10000.0), std::make_unique<hal::MemoryLines>(false));
  ControlHandler handler2(d2, {});
  r.args = {{"kind", "gravity"}, {"gravity_seconds", 4.0}, {"gravity_ramp_seconds", 0.25}};
  reply = handler2.handle(r);
  ASSERT_TRUE(reply.ok) << reply.error.message;
  CalibrationConfig expected;
  expected.kind = CalibrationKind::Gravity;
  expected.rate_hz = 10000.0;
  expected.gravity_seconds = 4.0;
  expected.gravity_ramp_seconds = 0.25;
  EXPECT_DOUBLE_EQ(reply.result["seconds"].get<double>(), CalibrationController(expected).seconds());
  expected.gravity_seconds = CalibrationConfig{}.gravity_seconds;
  EXPECT_LT(reply.result["seconds"].get<double>(), CalibrationController(expected).seconds());
}

}  // namespace
}  // namespace knoblab::hapticd
