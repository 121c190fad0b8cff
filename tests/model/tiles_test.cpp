// Prototyper tiles, Eq. 19 (position) and Eq. 20 (time), taken literally.
#include <gtest/gtest.h>

#include <vector>

#include "knoblab/model/tiles.hpp"

namespace knoblab::model {
namespace {

using V = std::vector<double>;

CubicSpline line(double x0, double y0, double x1, double y1) {
  return CubicSpline(V{x0, x1}, V{y0, y1});
}

TEST(PositionTile, IsEquation19InsideItsRange) {
  PositionTile tile;
  tile.theta_min = 0.0;
  tile.theta_max = 1.0;
  tile.f_pos = line(0.0, 2.0, 1.0, 4.0);   // stiffness 2 + 2θ
  tile.f_vel = line(0.0, 0.1, 1.0, 0.1);   // damping 0.1
  tile.f_acc = line(0.0, 0.0, 1.0, 0.02);  // mass 0.02θ
  const Kinematics<double> k{0.5, -2.0, 10.0};
  // f_pos(θ)·θ + f_vel(θ)·θ̇ + f_acc(θ)·θ̈ = 3·0.5 + 0.1·(−2) + 0.01·10
  EXPECT_NEAR(tile.torque(k), 1.5 - 0.2 + 0.1, 1e-14);
}

TEST(PositionTile, ContributesNothingOutsideItsRange) {
  PositionTile tile;
  tile.theta_min = -0.5;
  tile.theta_max = 0.5;
  tile.f_pos = line(-0.5, 1.0, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(tile.torque({0.5, 0.0, 0.0}), 0.5);  // closed range
  EXPECT_DOUBLE_EQ(tile.torque({-0.5, 0.0, 0.0}), -0.5);
  EXPECT_EQ(tile.torque({0.5001, 3.0, 3.0}), 0.0);
  EXPECT_EQ(tile.torque({-0.6, 3.0, 3.0}), 0.0);
}

TEST(PositionTile, AbsentFunctionsContributeNothing) {
  PositionTile tile;
  tile.theta_max = 1.0;
  EXPECT_EQ(tile.torque({0.5, 1.0, 1.0}), 0.0);
  tile.f_vel = line(0.0, 0.3, 1.0, 0.3);
  EXPECT_DOUBLE_EQ(tile.torque({0.5, 2.0, 100.0}), 0.6);
}

TEST(PositionTile, PeriodicSplineRepeatsAcrossAWideRange) {
  PositionTile tile;
  tile.theta_min = -10.0;
  tile.theta_max = 10.0;
  tile.f_vel = CubicSpline(V{0.0, 0.25, 0.5, 0.75, 1.0}, V{1.0, 2.0, 1.0, 0.0, 1.0},
                           SplineBoundary::kPeriodic);
  EXPECT_NEAR(tile.torque({0.25, 1.0, 0.0}), 2.0, 1e-12);
  EXPECT_NEAR(tile.torque({7.25, 1.0, 0.0}), 2.0, 1e-12);
  EXPECT_NEAR(tile.torque({-3.75, 1.0, 0.0}), 2.0, 1e-12);
}

TEST(TimeTile, IsEquation20WhileActive) {
  TimeTile tile;
  tile.duration = 2.0;
  tile.f_pos = line(0.0, 0.0, 2.0, 4.0);  // 2t
  tile.f_vel = line(0.0, 1.0, 2.0, 1.0);
  const Kinematics<double> k{0.3, 0.5, 7.0};
  EXPECT_NEAR(tile.torque(1.0, k), 2.0 * 0.3 + 0.5, 1e-14);
  EXPECT_NEAR(tile.torque(2.0, k), 4.0 * 0.3 + 0.5, 1e-14);
  EXPECT_EQ(tile.torque(2.01, k), 0.0);
  EXPECT_EQ(tile.torque(-0.01, k), 0.0);
}

TEST(TimeTile, LoopsWhenAsked) {
  TimeTile tile;
  tile.duration = 2.0;
  tile.loop = true;
  tile.f_pos = line(0.0, 0.0, 2.0, 4.0);
  const Kinematics<double> k{1.0, 0.0, 0.0};
  EXPECT_NEAR(tile.torque(5.0, k), tile.torque(1.0, k), 1e-14);
  EXPECT_NEAR(*tile.local_time(4.5), 0.5, 1e-14);
  EXPECT_FALSE(tile.local_time(-1.0).has_value());
  tile.duration = 0.0;
  EXPECT_FALSE(tile.local_time(0.0).has_value());
}

TEST(TimeTile, PlacedOnATimeLineItStartsLaterRunsOnItsOwnClockAndRepeatsEveryPeriod) {
  TimeTile tile;
  tile.start = 0.5;
  tile.duration = 0.25;
  tile.torque_of_time = line(0.0, 0.0, 0.25, 0.01);  // its own clock: 0 at its start
  const Kinematics<double> k{0.0, 0.0, 0.0};
  EXPECT_EQ(tile.torque(0.49, k), 0.0);
  EXPECT_NEAR(tile.torque(0.6, k), 0.004, 1e-12);
  EXPECT_EQ(tile.torque(0.8, k), 0.0);
  tile.loop = true;
  tile.period = 1.0;  // the line is a second long; this tile is its second half's first quarter
  EXPECT_NEAR(tile.torque(2.6, k), 0.004, 1e-12);
  EXPECT_EQ(tile.torque(2.3, k), 0.0);
  tile.period = 0.0;  // alone: it repeats as soon as it ends
  EXPECT_NEAR(*tile.local_time(0.75 + 0.6), 0.1, 1e-12);
}

TEST(Tiles, TotalTorqueSumsTiles) {
  std::vector<PositionTile> pos(2);
  pos[0].theta_min = 0.0;
  pos[0].theta_max = 1.0;
  pos[0].f_vel = line(0.0, 1.0, 1.0, 1.0);
  pos[1].theta_min = 0.5;
  pos[1].theta_max = 2.0;
  pos[1].f_acc = line(0.5, 2.0, 2.0, 2.0);
  const Kinematics<double> k{0.75, 3.0, 5.0};
  EXPECT_DOUBLE_EQ(total_torque(pos, k), 3.0 + 10.0);
  EXPECT_DOUBLE_EQ(total_torque(pos, Kinematics<double>{1.5, 3.0, 5.0}), 10.0);

  std::vector<TimeTile> time(2);
  time[0].duration = 1.0;
  time[0].f_vel = line(0.0, 1.0, 1.0, 1.0);
  time[1].duration = 3.0;
  time[1].f_vel = line(0.0, 2.0, 3.0, 2.0);
  EXPECT_DOUBLE_EQ(total_torque(time, 0.5, k), 9.0);
  EXPECT_DOUBLE_EQ(total_torque(time, 2.0, k), 6.0);
}

// ---- torque-valued curves (§5.3.1's torque waveforms) ----

TEST(PositionTile, TorqueCurvesAddTheirTorqueAtTheAngleAndTheVelocity) {
  PositionTile tile;
  tile.theta_min = -1.0;
  tile.theta_max = 1.0;
  tile.torque_of_angle = line(-1.0, -0.02, 1.0, 0.04);      // 0.01 + 0.03θ N·m
  tile.torque_of_velocity = line(-2.0, -0.004, 2.0, 0.004);  // 0.002 N·m·s/rad
  // Defined at θ = 0, unlike f_pos(θ)·θ.
  EXPECT_NEAR(tile.torque({0.0, 0.0, 0.0}), 0.01, 1e-15);
  EXPECT_NEAR(tile.torque({0.5, 1.0, 0.0}), 0.01 + 0.015 + 0.002, 1e-15);
  EXPECT_EQ(tile.torque({1.5, 1.0, 0.0}), 0.0) << "outside its span it adds nothing";
  EXPECT_NEAR(tile.stiffness_at(0.3), 0.03, 1e-12);
}

TEST(PositionTile, TorqueOfVelocityContinuesStraightBeyondItsLastKnot) {
  PositionTile tile;
  tile.theta_min = -1.0;
  tile.theta_max = 1.0;
  // A damping line that flattens towards ±1 rad/s: slope 0.001 at the ends
  // of a natural cubic (zero curvature there).
  tile.torque_of_velocity = CubicSpline(V{-1.0, -0.5, 0.0, 0.5, 1.0}, V{-0.003, -0.002, 0.0, 0.002, 0.003});
  const CubicSpline& g = *tile.torque_of_velocity;
  const double slope = g.derivative(1.0);
  ASSERT_GT(slope, 0.0);
  // Far beyond: the tangent line, not the natural spline's end cubic.
  EXPECT_NEAR(tile.torque({0.0, 40.0, 0.0}), 0.003 + slope * 39.0, 1e-12);
  EXPECT_NEAR(tile.torque({0.0, -40.0, 0.0}), -0.003 - g.derivative(-1.0) * 39.0, 1e-12);
  EXPECT_GT(tile.torque({0.0, 40.0, 0.0}), 0.0) << "a damping line keeps damping at any speed";
  const auto [lo, hi] = tile.velocity_slope_range(50.0);
  EXPECT_LE(lo, slope + 1e-12);
  EXPECT_GT(hi, 0.004) << "the steepest slope is near 0, between the knots";
}

TEST(PositionTile, MassAddsToTheVirtualMassInsideItsSpanOnly) {
  PositionTile a, b;
  a.theta_min = 0.0;
  a.theta_max = 1.0;
  a.mass = line(0.0, 1e-5, 1.0, 3e-5);
  b.theta_min = 0.5;
  b.theta_max = 2.0;
  b.mass = line(0.5, 1e-5, 2.0, 1e-5);
  const std::vector<PositionTile> tiles = {a, b};
  EXPECT_NEAR(total_mass(tiles, 0.25), 1.5e-5, 1e-18);
  EXPECT_NEAR(total_mass(tiles, 0.75), 2.5e-5 + 1e-5, 1e-18) << "overlapping tiles add up";
  EXPECT_EQ(total_mass(tiles, 3.0), 0.0);
  EXPECT_EQ(a.torque({0.5, 1.0, 100.0}), 0.0) << "mass is not rendered as a torque of θ̈";
}

TEST(TimeTile, TorqueCurveIsATorqueOverTime) {
  TimeTile tile;
  tile.duration = 1.0;
  tile.torque_of_time = line(0.0, 0.0, 1.0, 0.05);
  EXPECT_NEAR(tile.torque(0.4, {2.0, 3.0, 4.0}), 0.02, 1e-15) << "whatever the knob does";
  EXPECT_EQ(tile.torque(1.5, {2.0, 3.0, 4.0}), 0.0);
}

}  // namespace
}  // namespace knoblab::model
