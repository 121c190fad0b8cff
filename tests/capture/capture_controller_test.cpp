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

}  // namespace
}  // namespace knoblab::capture
