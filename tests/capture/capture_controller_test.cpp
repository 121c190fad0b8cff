// The capture controller against the plant simulator: position stimulus
// tracked by the PID, torque stimulus applied open loop.
#include <gtest/gtest.h>

#include <cmath>

#include "knoblab/capture/capture_controller.hpp"
#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/sim/presets.hpp"

namespace knoblab::capture {
namespace {

struct Recording {
  std::vector<Sample> samples;
};

Recording run(CaptureConfig cfg, const char* knob, sim::Load load, int cycles, double start_rad = 0.0) {
  sim::PlantConfig p;
  p.knob = *sim::presets::knob(knob);
  p.load = load;
  p.initial_angle = start_rad;
  SimDaq daq(p, cfg.rate_hz);
  SensorConfig sc;
  sc.rate_hz = cfg.rate_hz;
  sc.calibration = daq.calibration();
  SensorFrontEnd sensors(sc);
  CaptureController c(cfg);
  Recording r;
  for (int i = 0; i < cycles; ++i) {
    DaqInputs in;
    DaqOutputs out;
    Sample s;
    EXPECT_EQ(daq.read(in), IoStatus::ok);
    c.update(sensors.update(in), out, s);
    EXPECT_EQ(daq.write(out), IoStatus::ok);
    r.samples.push_back(s);
  }
  return r;
}

TEST(CaptureController, PositionStimulusIsTrackedByThePid) {
  CaptureConfig cfg;
  const Recording r = run(cfg, "subtle-detents", sim::Load::Knob, 15000);
  double worst = 0;
  for (const Sample& s : r.samples) worst = std::max(worst, std::abs(cfg.stimulus.theta(s.t) - s.theta));
  EXPECT_LT(worst, 0.01);  // rad, over 3 s of the Table 3 sweep
}

TEST(CaptureController, APositionSweepIsCentredWhereTheKnobStandsAtTheStart) {
  CaptureConfig cfg;
  const double start = 2.5;  // rad, where an earlier capture left it
  const Recording r = run(cfg, "subtle-detents", sim::Load::Knob, 15000, start);
  double worst = 0, fastest = 0;
  for (const Sample& s : r.samples) {
    worst = std::max(worst, std::abs(start + cfg.stimulus.theta(s.t) - s.theta));
    fastest = std::max(fastest, std::abs(s.omega));
  }
  EXPECT_LT(worst, 0.01);   // rad: no jump to the sweep's absolute zero
  EXPECT_LT(fastest, 5.0);  // rad/s: the sweep alone, no fling back to zero
}

TEST(CaptureController, TorqueStimulusIsAppliedOpenLoop) {
  CaptureConfig cfg;
  cfg.kind = CaptureConfig::Stimulus::Torque;
  cfg.torque_stimulus = model::TorqueSweep::from_hz(2.0, 10.0, 0.03, 2.0);  // 30 mN·m chirp
  const Recording r = run(cfg, "high-inertia", sim::Load::Knob, 10000);
  double sq = 0, moved = 0;
  for (const Sample& s : r.samples) {
    const double expected_V = cfg.torque_stimulus.torque(s.t) / cfg.torque_per_volt;
    ASSERT_NEAR(s.command, expected_V, 1e-12);
    moved = std::max(moved, std::abs(s.theta));
    // The knob's own torque (sensor) follows the applied one, less the rotor's share.
    const double err = s.torque - cfg.torque_stimulus.torque(s.t);
    sq += err * err;
  }
  EXPECT_GT(moved, 0.01);  // it turned the knob
  EXPECT_LT(std::sqrt(sq / static_cast<double>(r.samples.size())), 0.01);
}

TEST(CaptureController, TorqueStimulusIsClampedToTheDacRange) {
  CaptureConfig cfg;
  cfg.kind = CaptureConfig::Stimulus::Torque;
  cfg.torque_stimulus = model::TorqueSweep::from_hz(1.0, 1.0, 1.0, 1.0);  // 1 N·m: far beyond the amp
  const Recording r = run(cfg, "high-friction", sim::Load::Anchored, 3000);
  for (const Sample& s : r.samples) EXPECT_LE(std::abs(s.command), cfg.pid.limit_V);
}

// Feeds the controller readings `error(k)` rad behind its own reference (the
// sweep centred on the first reading, 0.5 rad) and returns the first cycle
// at which it says tracking is lost, or -1.
long long first_lost_cycle(const CaptureConfig& cfg, long long cycles, auto error) {
  CaptureController c(cfg);
  const double theta0 = 0.5;
  for (long long k = 0; k < cycles; ++k) {
    const double t = static_cast<double>(k) / cfg.rate_hz;
    SensorReading in;
    in.theta = theta0 + cfg.stimulus.theta(t) - (k == 0 ? 0.0 : error(k));
    DaqOutputs out;
    Sample s;
    c.update(in, out, s);
    if (c.tracking_lost()) return k;
  }
  return -1;
}

TEST(CaptureController, TrackingIsLostOnlyWhenTheErrorStaysPastTenPercentOfTheAmplitudeFor20ms) {
  CaptureConfig cfg;  // 5 kHz, Table 3's sweep (c = 1 rad): the limit is 0.1 rad, the hold 100 cycles
  EXPECT_DOUBLE_EQ(CaptureController(cfg).tracking_threshold_rad(), 0.1);
  // 99 cycles off, one back, 99 off again, either side: never 100 running.
  EXPECT_EQ(first_lost_cycle(cfg, 1000, [](long long k) { return k % 100 == 0 ? 0.0 : (k < 500 ? 0.11 : -0.11); }),
            -1);
  // Just inside the limit for ever: tracking holds.
  EXPECT_EQ(first_lost_cycle(cfg, 1000, [](long long) { return 0.0999; }), -1);
  // Off from cycle 10 on: lost on the hundredth cycle off, and it stays lost.
  EXPECT_EQ(first_lost_cycle(cfg, 1000, [](long long k) { return k >= 10 ? -0.101 : 0.0; }), 109);
  CaptureController c(cfg);
  SensorReading far;
  far.theta = 0.0;
  DaqOutputs out;
  Sample s;
  c.update(far, out, s);
  far.theta = 5.0;
  for (int k = 0; k < 100; ++k) c.update(far, out, s);
  far.theta = 0.0;
  c.update(far, out, s);  // back on the sweep: still lost
  EXPECT_TRUE(c.tracking_lost());
}

TEST(CaptureController, SmallSweepsAreJudgedAgainstTheTenMilliradianFloor) {
  CaptureConfig cfg;
  cfg.stimulus = model::SweptSine::torque_test();  // c = 0.02 rad: 10 % would be 2 mrad
  EXPECT_DOUBLE_EQ(CaptureController(cfg).tracking_threshold_rad(), 0.01);
  EXPECT_EQ(first_lost_cycle(cfg, 1000, [](long long) { return 0.009; }), -1);
  EXPECT_EQ(first_lost_cycle(cfg, 1000, [](long long) { return 0.011; }), 100);
}

TEST(CaptureController, TheHoldIsTimeNotCycles) {
  CaptureConfig cfg;
  cfg.rate_hz = 10000.0;  // 20 ms = 200 cycles
  EXPECT_EQ(first_lost_cycle(cfg, 1000, [](long long) { return 0.2; }), 200);
}

TEST(CaptureController, ATorqueStimulusHasNoTrackingToLose) {
  CaptureConfig cfg;
  cfg.kind = CaptureConfig::Stimulus::Torque;
  cfg.torque_stimulus = model::TorqueSweep::from_hz(1.0, 5.0, 0.01, 1.0);
  EXPECT_EQ(first_lost_cycle(cfg, 1000, [](long long) { return 3.0; }), -1);
}

// The five thesis knobs on Table 3's sweep for the 6 s of Eq. 9: far inside
// the limit (their worst is under half of it), so a real capture never trips.
TEST(CaptureController, TheThesisKnobsKeepTrackingOnTheTable3Sweep) {
  for (const char* knob : {"high-friction", "high-inertia", "subtle-detents", "moderate-detents", "non-sine-detents"}) {
    CaptureConfig cfg;
    sim::PlantConfig p;
    p.knob = *sim::presets::knob(knob);
    SimDaq daq(p, cfg.rate_hz);
    SensorConfig sc;
    sc.rate_hz = cfg.rate_hz;
    sc.calibration = daq.calibration();
    SensorFrontEnd sensors(sc);
    CaptureController c(cfg);
    double worst = 0;
    for (int i = 0; i < 30000; ++i) {
      DaqInputs in;
      DaqOutputs out;
      Sample s;
      ASSERT_EQ(daq.read(in), IoStatus::ok);
      c.update(sensors.update(in), out, s);
      ASSERT_EQ(daq.write(out), IoStatus::ok);
      worst = std::max(worst, std::abs(cfg.stimulus.theta(s.t) - s.theta));
    }
    EXPECT_FALSE(c.tracking_lost()) << knob;
    EXPECT_LT(worst, 0.5 * c.tracking_threshold_rad()) << knob;
  }
}

}  // namespace
}  // namespace knoblab::capture
