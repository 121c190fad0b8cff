// The benchmark's second plant (bench/discrepancy/two_body_plant.hpp): what
// its camera records, its stick-slip, its play and its coupling's ringing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/interchange/capture.hpp"
#include "two_body_plant.hpp"

namespace {

using namespace knoblab;
using bench::Coupling;
using bench::MotorStimulus;
using bench::TwoBodyConfig;
using bench::TwoBodyRun;

constexpr double kJ = 5e-5;  // kg·m²

// A slow ramp and back: every leg at `speed`, turning at `accel`.
MotorStimulus ramp(double amplitude, double speed, double accel) {
  MotorStimulus s;
  s.kind = MotorStimulus::Kind::Triangle;
  s.triangle = {amplitude, speed, speed, 1, accel};
  return s;
}

// A knob with Coulomb friction and a static excess: breakaway C + ΔC.
TwoBodyConfig sticky(double coulomb, double excess) {
  TwoBodyConfig c;
  c.knob.inertia = kJ;
  c.knob.coulomb_pos = c.knob.coulomb_neg = coulomb;
  c.knob.viscous_pos = c.knob.viscous_neg = 0.0;
  c.knob.static_excess = excess;
  c.knob.stribeck_speed = 0.005;
  c.camera.torque_noise_rms = 0.0;
  return c;
}

double rms(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / static_cast<double>(a.size()));
}

TEST(TwoBodyPlant, ARigidCouplingRecordsTheKnobsTorquesAndTheThesisFitRecoversThem) {
  TwoBodyConfig c;
  c.knob.inertia = 4.9e-5;
  c.knob.coulomb_pos = c.knob.coulomb_neg = 1.1e-3;
  c.knob.viscous_pos = 0.56e-3;
  c.knob.viscous_neg = 0.48e-3;
  c.knob.detent_amplitude = 11e-3;
  c.knob.detent_period = 1.0 / 12.0;
  c.knob.detent_phase = 0.4;
  c.coupling.stiffness = std::numeric_limits<double>::infinity();
  c.camera.torque_noise_rms = 0.1e-3;
  const TwoBodyRun run = bench::run_two_body(c);
  ASSERT_NO_THROW(interchange::validate(run.capture));
  EXPECT_EQ(run.capture.size(), 40000u);
  // The sensor adds exactly the noise asked for to what the knob takes.
  EXPECT_NEAR(rms(run.capture.torque, run.truth.coupling_torque), 0.1e-3, 0.003e-3);
  // The knob is the motor, and the motor is the Table 3 sweep.
  for (std::size_t i = 0; i < run.capture.size(); i += 997) {
    EXPECT_EQ(run.truth.knob_theta[i], run.truth.motor_theta[i]);
    EXPECT_NEAR(run.truth.motor_theta[i], model::SweptSine::spatial().theta(run.capture.t[i]), 1e-12);
  }

  const fit::FitResult f = fit::fit_knob(fit::prepare(run.capture));
  ASSERT_TRUE(f.detents);
  EXPECT_NEAR(f.value("M_acc"), 4.9e-5, 0.03 * 4.9e-5);
  EXPECT_NEAR(f.value("C_vel_pos"), 1.1e-3, 0.1 * 1.1e-3);
  EXPECT_NEAR(f.value("C_vel_neg"), 1.1e-3, 0.1 * 1.1e-3);
  EXPECT_NEAR(f.value("B_vel_pos"), 0.56e-3, 0.1 * 0.56e-3);
  EXPECT_NEAR(f.value("B_vel_neg"), 0.48e-3, 0.1 * 0.48e-3);
  EXPECT_NEAR(std::abs(f.value("A_pos")), 11e-3, 0.02 * 11e-3);
  EXPECT_NEAR(f.value("P_pos"), 1.0 / 12.0, 0.005 / 12.0);
}

TEST(TwoBodyPlant, AKnobUnderLessThanItsBreakawayTorqueNeverMoves) {
  // k·amplitude = 6 mN·m against a 10 mN·m breakaway, back and forth.
  TwoBodyConfig c = sticky(2e-3, 8e-3);
  c.coupling = {20.0, Coupling::damping_for(0.1, 20.0, kJ), 0.0};
  c.stimulus = ramp(0.3e-3, 0.02, 20.0);
  c.seconds = 1.0;
  const TwoBodyRun run = bench::run_two_body(c);
  const auto [lo, hi] = std::minmax_element(run.truth.coupling_torque.begin(), run.truth.coupling_torque.end());
  EXPECT_GT(*hi, 5e-3);  // the motor does push, both ways
  EXPECT_LT(*lo, -5e-3);
  for (std::size_t i = 0; i < run.capture.size(); ++i) {
    ASSERT_EQ(run.truth.knob_theta[i], run.truth.knob_theta.front()) << "sample " << i;
    ASSERT_TRUE(run.truth.stuck[i]) << "sample " << i;
  }
}

TEST(TwoBodyPlant, AStuckKnobBreaksAwayWhenTheCouplingTorqueReachesTheBreakawayLevel) {
  TwoBodyConfig c = sticky(2e-3, 8e-3);
  c.coupling = {20.0, Coupling::damping_for(0.1, 20.0, kJ), 0.0};
  c.stimulus = ramp(0.5, 0.02, 20.0);
  c.seconds = 1.0;
  const TwoBodyRun run = bench::run_two_body(c);
  const auto& stuck = run.truth.stuck;
  const std::size_t slip = static_cast<std::size_t>(std::find(stuck.begin(), stuck.end(), 0) - stuck.begin());
  ASSERT_GT(slip, 1u);
  ASSERT_LT(slip, stuck.size());
  for (std::size_t i = 0; i < slip; ++i) ASSERT_EQ(run.truth.knob_theta[i], run.truth.knob_theta.front());
  // The torque climbs k·0.02 rad/s = 0.08 mN·m a sample: the last stuck
  // sample sits within a climb of the 10 mN·m breakaway.
  EXPECT_NEAR(run.truth.coupling_torque[slip - 1], 10e-3, 0.1e-3);
  // Then it follows the motor, within a breakaway's twist.
  const double motor_travel = run.truth.motor_theta.back() - run.truth.motor_theta.front();
  EXPECT_GT(motor_travel, 0.015);
  EXPECT_NEAR(run.truth.knob_theta.back() - run.truth.knob_theta.front(), motor_travel, 10e-3 / 20.0);
}

TEST(TwoBodyPlant, AfterAReversalTheKnobStandsWhileTheMotorCrossesThePlay) {
  constexpr double kPlay = 3e-3, kK = 2000.0, kSpeed = 0.2;
  TwoBodyConfig c = sticky(5e-3, 2e-3);
  c.coupling = {kK, Coupling::damping_for(0.2, kK, kJ), kPlay};
  c.stimulus = ramp(0.2, kSpeed, 20.0);
  c.seconds = 2.0;
  const TwoBodyRun run = bench::run_two_body(c);
  const auto& motor = run.truth.motor_theta;
  const auto& knob = run.truth.knob_theta;
  // The first turn, at +0.2 rad, and the first sample the knob moves after it.
  const std::size_t turn =
      static_cast<std::size_t>(std::max_element(motor.begin(), motor.begin() + 8000) - motor.begin());
  ASSERT_NEAR(motor[turn], 0.2, 1e-6);
  std::size_t moved = turn;
  while (moved < knob.size() && knob[moved] == knob[turn]) ++moved;
  ASSERT_LT(moved, knob.size());
  EXPECT_LT(knob[moved], knob[turn]);  // back the other way
  // Meanwhile the motor went back by the play, plus unwinding the coupling
  // from the turn and winding it to the breakaway on the other face.
  const double travel = motor[turn] - motor[moved];
  const double windings = (run.truth.coupling_torque[turn] + 7e-3) / kK;
  EXPECT_GE(travel, kPlay);
  EXPECT_LE(travel, kPlay + windings + 2 * kSpeed / c.camera.rate_hz);
  // Across the play the faces do not touch and the sensor reads nothing.
  std::size_t loose = 0;
  for (std::size_t i = turn; i < moved; ++i) {
    if (!run.truth.in_play[i]) continue;
    ++loose;
    EXPECT_EQ(run.truth.coupling_torque[i], 0.0);
  }
  EXPECT_GE(static_cast<double>(loose), 0.9 * kPlay / kSpeed * c.camera.rate_hz);
}

TEST(TwoBodyPlant, ASoftCouplingRingsAtItsNaturalFrequencyAfterABreakaway) {
  constexpr double kK = 20.0;
  const double f_n = std::sqrt(kK / kJ) / (2.0 * std::numbers::pi);  // 100.7 Hz
  TwoBodyConfig c = sticky(1e-3, 5e-3);
  c.coupling = {kK, Coupling::damping_for(0.03, kK, kJ), 0.0};
  // The motor cruises at 1 rad/s 5 ms after it starts, a few ms after the
  // breakaway: from then on nothing but the coupling moves the torque's mean.
  c.stimulus = ramp(0.5, 1.0, 200.0);
  c.camera.torque_noise_rms = 0.05e-3;
  c.seconds = 0.5;
  const TwoBodyRun run = bench::run_two_body(c);
  const auto& stuck = run.truth.stuck;
  const std::size_t slip = static_cast<std::size_t>(std::find(stuck.begin(), stuck.end(), 0) - stuck.begin());
  // 50 ms of the recorded torque from 5 ms after the breakaway, about its
  // mean: the knob slides throughout, so the coupling rings freely.
  const std::size_t from = slip + 25, n = 250;
  ASSERT_LT(from + n, stuck.size());
  double mean = 0.0;
  for (std::size_t i = from; i < from + n; ++i) {
    ASSERT_FALSE(stuck[i]);
    mean += run.capture.torque[i] / static_cast<double>(n);
  }
  std::vector<double> crossings;  // s, interpolated between samples
  for (std::size_t i = from + 1; i < from + n; ++i) {
    const double a = run.capture.torque[i - 1] - mean, b = run.capture.torque[i] - mean;
    if ((a < 0.0) != (b < 0.0)) crossings.push_back(run.capture.t[i - 1] + a / (a - b) / c.camera.rate_hz);
  }
  ASSERT_GE(crossings.size(), 9u);
  const double f = 0.5 * static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());
  EXPECT_NEAR(f, f_n, 0.02 * f_n);
}

TEST(TwoBodyPlant, AKnobSideAccelerometerReadsTheKnobsAccelerationNotTheMotors) {
  TwoBodyConfig c = sticky(1e-3, 5e-3);
  c.coupling = {20.0, Coupling::damping_for(0.03, 20.0, kJ), 0.0};
  c.stimulus = ramp(0.5, 1.0, 200.0);
  c.camera.accelerometer = true;
  c.seconds = 0.2;
  const TwoBodyRun run = bench::run_two_body(c);
  ASSERT_FALSE(run.capture.alpha_derived);
  ASSERT_TRUE(run.capture.omega_derived);
  const auto& stuck = run.truth.stuck;
  const std::size_t slip = static_cast<std::size_t>(std::find(stuck.begin(), stuck.end(), 0) - stuck.begin());
  ASSERT_GT(slip, 0u);
  for (std::size_t i = 0; i < slip; ++i) EXPECT_EQ(run.capture.alpha[i], 0.0) << "stuck sample " << i;
  // Ringing after the breakaway, while the motor cruises (α = 0): the
  // accelerometer follows the knob's speed, sample to sample.
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = slip + 25; i < slip + 250; ++i) {
    const double slope = (run.truth.knob_omega[i + 1] - run.truth.knob_omega[i - 1]) * c.camera.rate_hz / 2.0;
    worst = std::max(worst, std::abs(run.capture.alpha[i] - slope));
    largest = std::max(largest, std::abs(slope));
  }
  EXPECT_GT(largest, 50.0);  // rad/s²: the knob rings, the motor does not
  EXPECT_LT(worst, 0.05 * largest);
}

TEST(TwoBodyPlant, ASettingOutsideItsRangeIsRefusedByName) {
  const auto refused = [](TwoBodyConfig c, const std::string& field) {
    try {
      bench::run_two_body(c);
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << field << " was accepted";
  };
  TwoBodyConfig c;
  c.knob.inertia = 0.0;
  refused(c, "knob.inertia must be finite and > 0 kg·m², got 0");
  c = {};
  c.knob.stribeck_speed = -1.0;
  refused(c, "knob.stribeck_speed");
  c = {};
  c.coupling.play = 1e-3;
  c.coupling.stiffness = std::numeric_limits<double>::infinity();
  refused(c, "coupling.play needs a finite coupling.stiffness");
  c = {};
  c.camera.torque_noise_rms = std::nan("");
  refused(c, "camera.torque_noise_rms");
  c = {};
  c.camera.accelerometer_noise_rms = -1.0;
  refused(c, "camera.accelerometer_noise_rms must be finite and ≥ 0, got -1");
  c = {};
  c.stimulus = ramp(0.5, 1.0, 20.0);
  c.stimulus.triangle.fastest_rad_s = 0.5;
  refused(c, "stimulus.triangle.fastest_rad_s must be finite and at least slowest_rad_s");
}

TEST(TwoBodyPlant, TheTriangleSweepClimbsItsSpeedLadderBetweenTurnsAtItsAmplitude) {
  MotorStimulus s;
  s.kind = MotorStimulus::Kind::Triangle;
  s.triangle = {0.5, 0.1, 1.6, 5, 50.0};  // 0.1, 0.2, 0.4, 0.8, 1.6 rad/s
  const bench::MotorPath path(s, 40.0);
  double top = 0.0, bottom = 0.0, fastest = 0.0, direction = 1.0;
  std::vector<double> leg_speeds;  // the top speed of each leg, in order
  for (double t = 0.0; t < 40.0; t += 2e-4) {
    const bench::MotorState m = path.at(t);
    top = std::max(top, m.theta);
    bottom = std::min(bottom, m.theta);
    if (m.omega * direction < 0.0) {  // turned
      leg_speeds.push_back(fastest);
      fastest = 0.0;
      direction = -direction;
    }
    fastest = std::max(fastest, std::abs(m.omega));
  }
  EXPECT_NEAR(top, 0.5, 1e-9);
  EXPECT_NEAR(bottom, -0.5, 1e-9);
  const double ladder[] = {0.1, 0.2, 0.4, 0.8, 1.6, 0.8, 0.4, 0.2, 0.1};
  ASSERT_GE(leg_speeds.size(), std::size(ladder));
  for (std::size_t i = 0; i < std::size(ladder); ++i) EXPECT_NEAR(leg_speeds[i], ladder[i], 1e-9) << "leg " << i;
}

}  // namespace
