// Sensor models: torque sensor, encoder, accelerometer.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "helpers.hpp"
#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"

using namespace knoblab::sim;

namespace {
constexpr double kLsb = 20.0 / 65536.0;  // 16 bit over ±10 V
}

TEST(TorqueSensor, ScaleIsThesisCalibration) {
  const TorqueSensorScale s;
  EXPECT_NEAR(s.to_volts(0.1755), 5.0, 1e-12);
  EXPECT_NEAR(s.to_torque(5.0), 0.1755, 1e-12);
}

TEST(TorqueSensor, SaturatesAt180mNm) {
  TorqueSensorParams p;
  p.noise_sigma = 0.0;
  Rng rng(1);
  const TorqueSensorScale s;
  EXPECT_NEAR(s.to_torque(p.sample(0.3, rng)), 0.180, s.to_torque(kLsb));
  EXPECT_NEAR(s.to_torque(p.sample(-0.3, rng)), -0.180, s.to_torque(kLsb));
  EXPECT_NEAR(s.to_torque(p.sample(0.1, rng)), 0.1, s.to_torque(kLsb));
}

TEST(TorqueSensor, SaturatesInThePlant) {
  // Gripper clamped, full 12 V command: the motor makes 181 mN·m, the sensor
  // stops at 180.
  PlantConfig c = test::quiet({});
  c.load = Load::Anchored;
  Plant p(c);
  for (int n = 0; n < 1000; ++n) p.step(12.0, 1e-4);
  EXPECT_NEAR(p.state().coupling_torque, 0.181, 1e-5);
  EXPECT_NEAR(p.readings().torque, 0.180, p.torque_scale().to_torque(kLsb));
  for (int n = 0; n < 1000; ++n) p.step(6.0, 1e-4);
  EXPECT_NEAR(p.readings().torque, 0.0905, p.torque_scale().to_torque(kLsb));
}

TEST(TorqueSensor, VoltsAreAdcCodes) {
  TorqueSensorParams p;
  Rng rng(7);
  for (int n = 0; n < 1000; ++n) {
    const double v = p.sample(0.05 * std::sin(n * 0.01), rng);
    const double code = v / kLsb;
    ASSERT_NEAR(code, std::round(code), 1e-9) << v;
  }
  // One code is 10.7 µN·m.
  EXPECT_NEAR(TorqueSensorScale{}.to_torque(kLsb), 10.7e-6, 0.05e-6);
}

TEST(TorqueSensor, OffsetShiftsTheReading) {
  PlantConfig c = test::quiet({});
  c.load = Load::Anchored;
  c.torque_sensor.offset = 0.002;
  Plant p(c);
  p.step(0.0, 1e-4);
  EXPECT_NEAR(p.readings().torque, 0.002, p.torque_scale().to_torque(kLsb));
}

TEST(TorqueSensor, NoiseHasTheConfiguredSigma) {
  TorqueSensorParams p;
  Rng rng(3);
  double sum = 0, sum2 = 0;
  const int n = 200000;
  const TorqueSensorScale s;
  for (int i = 0; i < n; ++i) {
    const double t = s.to_torque(p.sample(0.01, rng)) - 0.01;
    sum += t;
    sum2 += t * t;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 2e-6);
  EXPECT_NEAR(sd, 0.05e-3, 0.002e-3);
}

TEST(Encoder, QuantisesTo640000CountsPerRev) {
  const EncoderScale e;
  const double step = 2 * std::numbers::pi / 640000;
  EXPECT_DOUBLE_EQ(e.rad_per_count(), step);
  EXPECT_EQ(e.to_counts(2 * std::numbers::pi), 640000);
  EXPECT_EQ(e.to_counts(0.4 * step), 0);
  EXPECT_EQ(e.to_counts(1.6 * step), 1);
  EXPECT_EQ(e.to_counts(-0.4 * step), -1);  // floor, like a counter
  EXPECT_EQ(e.to_counts(1000.5 * step), 1000);
}

TEST(Encoder, PlantReportsTheMotorShaftInCounts) {
  PlantConfig c = test::quiet({});
  c.load = Load::Free;
  Plant p(c);
  for (int n = 0; n < 200; ++n) {
    p.step(0.02, 1e-4);
    const double th = p.state().motor_angle;
    const double back = p.encoder_scale().to_angle(p.readings().encoder_counts);
    ASSERT_LE(back, th);
    ASSERT_GT(back, th - p.encoder_scale().rad_per_count());
  }
  EXPECT_GT(p.readings().encoder_counts, 100);
}

TEST(Accelerometer, GravityAmplitudeAndPhaseAtRest) {
  const double roll = 0.3;
  PlantConfig c = test::quiet({});
  c.load = Load::Anchored;
  c.mounting = CameraOrientation::lab(roll);
  const double A = kGravity / 0.015;  // horizontal axis: 653.8 rad/s²
  for (double theta : {0.0, 1.0, std::numbers::pi / 2 - roll, 4.0}) {
    c.initial_angle = theta;
    Plant p(c);
    p.step(0.0, 1e-4);
    const double expected = A * std::sin(theta + roll);
    EXPECT_NEAR(p.readings().accel_volts * 1148.0, expected, 1148.0 * kLsb) << theta;
    // The stored calibration undoes it: α = 0 at rest.
    EXPECT_NEAR(p.accel_calibration().to_alpha(p.readings().accel_volts, theta), 0.0,
                1148.0 * kLsb);
  }
  const AccelCalibration cal = Plant(c).accel_calibration();
  EXPECT_DOUBLE_EQ(cal.C_cal, 1148.0);
  EXPECT_NEAR(cal.A, A, 1e-9);
  EXPECT_DOUBLE_EQ(cal.B, 1.0);
  EXPECT_DOUBLE_EQ(cal.C, roll);
  EXPECT_DOUBLE_EQ(cal.D, 0.0);
}

TEST(Accelerometer, TiltScalesGravity) {
  EXPECT_DOUBLE_EQ(CameraOrientation::vertical().gravity_amplitude(0.015), 0.0);
  EXPECT_NEAR(CameraOrientation::tripod(std::numbers::pi / 6).gravity_amplitude(0.015),
              0.5 * kGravity / 0.015, 1e-9);
  PlantConfig c = test::quiet({});
  c.load = Load::Anchored;
  c.mounting = CameraOrientation::vertical();
  c.accel.offset = 5.0;  // D_g
  c.initial_angle = 1.0;
  Plant p(c);
  p.step(0.0, 1e-4);
  EXPECT_NEAR(p.readings().accel_volts * 1148.0, 5.0, 1148.0 * kLsb);
}

TEST(Accelerometer, MeasuresAngularAccelerationThroughCcal) {
  // Free motor under constant current: α = K·i/J (minus b·ω/J).
  PlantConfig c = test::quiet({});
  c.load = Load::Free;
  c.mounting = CameraOrientation::lab(0.7);
  Plant p(c);
  for (int n = 0; n < 50; ++n) p.step(0.004, 1e-4);  // 5 ms: current and filter settled
  const double alpha_true = p.state().motor_accel;
  EXPECT_NEAR(alpha_true, 0.0438 * p.state().current / 1e-6, 1.0);
  ASSERT_GT(alpha_true, 50.0);
  const double theta = p.encoder_scale().to_angle(p.readings().encoder_counts);
  const double alpha = p.accel_calibration().to_alpha(p.readings().accel_volts, theta);
  EXPECT_NEAR(alpha, alpha_true, 1.0);
  // Volts sign: positive α raises the raw channel.
  const double gravity = p.accel_calibration().gravity(p.state().motor_angle);
  EXPECT_NEAR(p.readings().accel_volts, (alpha_true + gravity) / 1148.0, 2 * kLsb);
}

TEST(Accelerometer, NoiseIsFourPercentOfFullScalePeakToPeak) {
  AccelerometerParams a;
  EXPECT_NEAR(a.full_scale(), 2 * kGravity / 0.015, 1e-9);
  EXPECT_NEAR(a.noise_sigma(), 0.04 * a.full_scale() / 6.0, 1e-12);  // ≈ 8.7 rad/s²
  Accelerometer acc(a, CameraOrientation::vertical());
  acc.reset(0.0);
  Rng rng(5);
  double sum2 = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double x = acc.sample(rng) * a.C_cal;
    sum2 += x * x;
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), a.noise_sigma(), 0.02 * a.noise_sigma());
}
