// The renderer against a hand that moves the knob along a known path: the
// motor command must be minus the model torque of that motion.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "knoblab/hapticd/render_controller.hpp"

namespace knoblab::hapticd {
namespace {

constexpr double kRate = 10000.0, kDt = 1.0 / kRate;

capture::SensorConfig sensor_config() {
  capture::SensorConfig c;
  c.rate_hz = kRate;
  return c;
}

struct Bench {
  RenderConfig cfg;
  RenderController rc{cfg};
  capture::SensorCalibration cal;
  capture::SensorFrontEnd sensors{sensor_config()};

  // Drives the hand path θ(t) for n cycles; returns the last command.
  double run(const std::function<double(double)>& theta, int n, int start = 0,
             double measured_torque = 0.0, std::vector<double>* commands = nullptr) {
    capture::DaqOutputs out;
    capture::Sample s;
    for (int i = start; i < start + n; ++i) {
      capture::DaqInputs in;
      in.encoder_counts = static_cast<std::int64_t>(std::floor(theta(i * kDt) / (2 * M_PI / cal.counts_per_rev)));
      in.torque_V = measured_torque / cal.torque_Nm_per_V;
      rc.take_tiles();  // as the core does, every cycle
      rc.update(sensors.update(in), out, s);
      if (commands) commands->push_back(out.motor_command_V);
    }
    return out.motor_command_V;
  }
  double torque_of(double volts) const { return -volts * cfg.torque_per_volt; }
};

TEST(RenderController, DampingOpposesMotion) {
  Bench b;
  RenderParams p;
  p.B_vel = 0.01;
  b.rc.set_params(p, true);
  const double v = b.run([](double t) { return 2.0 * t; }, 3000);
  EXPECT_NEAR(b.torque_of(v), 0.01 * 2.0, 0.0005);
  EXPECT_LT(v, 0.0);  // the motor pushes against the motion
}

TEST(RenderController, DetentsFollowAmplitudeAndPeriod) {
  Bench b;
  RenderParams p;
  p.A_pos = 0.02;
  p.P_pos = 1.0 / 12.0;
  b.rc.set_params(p, true);
  auto path = [](double t) { return 0.3 * t; };
  for (int n : {1000, 1377, 2500}) {
    const double v = b.run(path, 1, n);
    const double theta = std::floor(path(n * kDt) / (2 * M_PI / 640000.0)) * (2 * M_PI / 640000.0);
    EXPECT_NEAR(b.torque_of(v), 0.02 * std::sin(theta * 12.0), 1e-4) << n;
  }
}

TEST(RenderController, VirtualMassRendersInertia) {
  Bench b;
  RenderParams p;
  p.M_acc = 0.2e-3;
  b.rc.set_params(p, true);
  const double v = b.run([](double t) { return 10.0 * t * t; }, 5000);  // α = 20 rad/s²
  EXPECT_NEAR(b.torque_of(v), 0.2e-3 * 20.0, 0.05 * 0.2e-3 * 20.0);
}

TEST(RenderController, ParameterChangesRampWithoutASteps) {
  Bench b;
  std::vector<double> cmds;
  auto still = [](double) { return 0.131; };  // a detent flank: full torque change if A jumped
  b.run(still, 100, 0, 0.0, &cmds);
  RenderParams p;
  p.A_pos = 0.05;
  p.P_pos = 1.0 / 12.0;
  b.rc.set_params(p);  // ramped
  b.run(still, 1000, 100, 0.0, &cmds);
  double biggest_step = 0;
  for (std::size_t i = 1; i < cmds.size(); ++i) biggest_step = std::max(biggest_step, std::abs(cmds[i] - cmds[i - 1]));
  const double full = std::abs(b.torque_of(cmds.back()));
  EXPECT_NEAR(full, 0.05 * std::abs(std::sin(0.131 * 12.0)), 1e-4);  // reached after the ramp
  EXPECT_LT(b.torque_of(biggest_step) * -1.0, full / 100.0);       // ≈ 500 small steps, no jump
}

TEST(RenderController, StickBandHoldsUpToTheStaticLimit) {
  Bench b;
  RenderParams p;
  p.stick = true;
  p.dv = 0.01;
  p.D_neg = 0.02;
  p.D_pos = 0.03;
  b.rc.set_params(p, true);
  auto still = [](double) { return 0.0; };
  EXPECT_NEAR(b.torque_of(b.run(still, 200, 0, 0.015)), 0.015, 1e-4);   // held
  EXPECT_NEAR(b.torque_of(b.run(still, 200, 200, 0.5)), 0.03, 1e-4);    // breaks away
  EXPECT_NEAR(b.torque_of(b.run(still, 200, 400, -0.5)), -0.02, 1e-4);
}

TEST(RenderController, EffectsAreRenderedThroughTheLibraryTerms) {
  Bench b;
  RenderParams p;
  p.B_vel = 0.002;
  p.effects.gravity = {0.02, 0.5};
  p.effects.stribeck = {0.004, 0.5};
  b.rc.set_params(p, true);
  auto path = [](double t) { return 0.4 + 0.2 * t; };  // 0.2 rad/s: Stribeck near its full excess
  const double v = b.run(path, 3000);
  const double theta = path(2999 * kDt), omega = 0.2;
  const double expected = 0.002 * omega + 0.02 * std::sin(theta + 0.5) + 0.004 * std::exp(-(omega / 0.5) * (omega / 0.5));
  EXPECT_NEAR(b.torque_of(v), expected, 2e-4);
  // Without them the command is the bare Eq. 14, far from it.
  RenderParams bare;
  bare.B_vel = 0.002;
  b.rc.set_params(bare, true);
  EXPECT_NEAR(b.torque_of(b.run(path, 1, 3000)), 0.002 * omega, 2e-4);
}

TEST(RenderController, ANewEffectSetFadesTheOldOutAndItselfInWithoutAStep) {
  Bench b;
  std::vector<double> cmds;
  auto still = [](double) { return 0.131; };
  RenderParams p;
  p.effects.offset.tau0 = 0.03;
  b.rc.set_params(p, true);
  b.run(still, 100, 0, 0.0, &cmds);
  p.effects.offset.tau0 = 0.0;
  p.effects.gravity = {0.04, 0.0};
  b.rc.set_params(p);  // faded
  b.run(still, 1000, 100, 0.0, &cmds);
  double biggest_step = 0;
  for (std::size_t i = 1; i < cmds.size(); ++i) biggest_step = std::max(biggest_step, std::abs(cmds[i] - cmds[i - 1]));
  EXPECT_NEAR(b.torque_of(cmds[99]), 0.03, 1e-6);                          // the old set, whole
  EXPECT_NEAR(b.torque_of(cmds.back()), 0.04 * std::sin(0.131), 1e-6);      // the new one, whole
  EXPECT_LT(std::abs(b.torque_of(biggest_step)), 0.03 / 100.0);            // ≈ 250 steps each way, no jump
  // Base parameters alone (a slider drag) leave the effects as they are.
  RenderParams drag = p;
  drag.B_vel = 0.001;
  b.rc.set_params(drag);
  EXPECT_NEAR(b.torque_of(b.run(still, 1, 1100)), 0.04 * std::sin(0.131), 1e-6);
}

}  // namespace
}  // namespace knoblab::hapticd

namespace knoblab::hapticd {
namespace {

TEST(RenderController, PositionAndTimeTilesAddToTheModel) {
  Bench b;
  // A position tile: stiffness f_pos(θ) = 0.5 N·m/rad between 0 and 1 rad (Eq. 19).
  const std::vector<double> x = {0.0, 0.5, 1.0}, k = {0.5, 0.5, 0.5};
  auto tiles = std::make_unique<TileSet>();
  model::PositionTile pt;
  pt.f_pos = model::CubicSpline(x, k);
  pt.theta_min = 0.0;
  pt.theta_max = 1.0;
  tiles->position.push_back(pt);
  ASSERT_TRUE(b.rc.load_tiles(std::move(tiles)));
  auto at = [](double) { return 0.4; };
  // Faded in over the ramp (500 cycles), then f_pos(θ)·θ.
  EXPECT_NEAR(b.torque_of(b.run(at, 600)), 0.5 * 0.4, 1e-4);
  auto outside = [](double) { return 1.5; };
  EXPECT_NEAR(b.torque_of(b.run(outside, 50, 600)), 0.0, 1e-4);

  // Replace with a time tile: f_pos(t) = 0.1·t for 1 s (Eq. 20), at θ = 0.4.
  auto next = std::make_unique<TileSet>();
  model::TimeTile tt;
  const std::vector<double> ts = {0.0, 0.5, 1.0}, ramp = {0.0, 0.05, 0.1};
  tt.f_pos = model::CubicSpline(ts, ramp);
  tt.duration = 1.0;
  next->time.push_back(tt);
  ASSERT_TRUE(b.rc.load_tiles(std::move(next)));
  const double v = b.run(at, 5001, 650);  // 0.5 s after the set started
  EXPECT_NEAR(b.torque_of(v), 0.05 * 0.4, 1e-3);
  // Clearing fades to the bare model (here: nothing).
  ASSERT_TRUE(b.rc.load_tiles(nullptr));
  EXPECT_NEAR(b.torque_of(b.run(at, 600, 6000)), 0.0, 1e-6);
}

// A set with a torque curve, at a fixed angle.
std::unique_ptr<TileSet> constant_torque(double tau) {
  auto set = std::make_unique<TileSet>();
  model::PositionTile t;
  t.theta_min = -1.0;
  t.theta_max = 1.0;
  const std::vector<double> x = {-1.0, 1.0}, y = {tau, tau};
  t.torque_of_angle = model::CubicSpline(x, y);
  set->position.push_back(t);
  return set;
}

double largest_step(const std::vector<double>& v) {
  double m = 0.0;
  for (std::size_t i = 1; i < v.size(); ++i) m = std::max(m, std::abs(v[i] - v[i - 1]));
  return m;
}

TEST(RenderController, ANewTileSetCrossFadesFromTheOldOneWithoutAStepInTorque) {
  Bench b;
  auto at = [](double) { return 0.3; };
  ASSERT_TRUE(b.rc.load_tiles(constant_torque(0.06)));  // +60 mN·m at the knob's angle
  EXPECT_NEAR(b.torque_of(b.run(at, 600)), 0.06, 1e-9);
  // Swapped for −60 mN·m while playing: 120 mN·m between the two sets.
  ASSERT_TRUE(b.rc.load_tiles(constant_torque(-0.06)));
  std::vector<double> volts;
  b.run(at, 700, 600, 0.0, &volts);
  std::vector<double> torque;
  for (const double v : volts) torque.push_back(b.torque_of(v));
  EXPECT_NEAR(torque.front(), 0.06, 1e-9) << "the swap's first cycle still feels the old set";
  EXPECT_NEAR(torque.back(), -0.06, 1e-9);
  // Linear over kParamRampSeconds (500 cycles): 0.12 N·m / 500 = 0.24 mN·m
  // a cycle, where swapping at once stepped by all 120 mN·m.
  EXPECT_LT(largest_step(torque), 0.12 / 400.0);
  EXPECT_NEAR(torque[250], 0.0, 0.12 / 400.0) << "halfway, the two sets weigh the same";
}

TEST(RenderController, AnotherSetWaitsUntilTheFadeIsOverAndTheOldSetComesBackForDeletion) {
  Bench b;
  auto at = [](double) { return 0.3; };
  ASSERT_TRUE(b.rc.load_tiles(constant_torque(0.02)));
  b.run(at, 1);  // taken: fading in
  ASSERT_TRUE(b.rc.load_tiles(constant_torque(0.04)));  // offered, waits for the fade
  auto third = constant_torque(0.08);
  EXPECT_FALSE(b.rc.load_tiles(std::move(third))) << "one offer at a time";
  ASSERT_TRUE(third);
  b.run(at, 100, 1);
  EXPECT_NEAR(b.torque_of(b.run(at, 1, 101)), 0.02 * 101.0 / 500.0, 1e-6) << "still the first set fading in";
  b.run(at, 1000, 102);
  EXPECT_NEAR(b.torque_of(b.run(at, 1, 1102)), 0.04, 1e-9);
  EXPECT_TRUE(b.rc.load_tiles(std::move(third))) << "taken once both fades are over";
  b.run(at, 600, 1103);
  EXPECT_NEAR(b.torque_of(b.run(at, 1, 1703)), 0.08, 1e-9);
}

TEST(Handoff, OffersAreTakenInOrderAndOldObjectsComeBackForDeletion) {
  Handoff<int> h;
  EXPECT_EQ(h.current(), nullptr);
  ASSERT_TRUE(h.publish(std::make_unique<int>(1)));
  EXPECT_FALSE(h.publish(std::make_unique<int>(2)));  // not yet taken
  EXPECT_EQ(*h.current(), 1);
  ASSERT_TRUE(h.publish(std::make_unique<int>(3)));
  EXPECT_EQ(*h.current(), 3);
  ASSERT_TRUE(h.publish(nullptr));
  auto kept = std::make_unique<int>(5);
  EXPECT_FALSE(h.publish(std::move(kept)));  // "none" is not yet taken
  ASSERT_TRUE(kept) << "a refused offer stays with the caller, to offer again";
  EXPECT_EQ(h.current(), nullptr);
  ASSERT_TRUE(h.publish(std::move(kept)));
  EXPECT_EQ(*h.current(), 5);
}

TEST(Handoff, AFadingLoopKeepsTheReplacedObjectUntilItReleasesIt) {
  Handoff<int> h;
  ASSERT_TRUE(h.publish(std::make_unique<int>(1)));
  ASSERT_TRUE(h.take_keeping_previous());
  ASSERT_TRUE(h.release_previous());  // nothing before it
  ASSERT_TRUE(h.publish(std::make_unique<int>(2)));
  ASSERT_TRUE(h.take_keeping_previous());
  EXPECT_EQ(*h.held(), 2);
  ASSERT_TRUE(h.previous());
  EXPECT_EQ(*h.previous(), 1) << "alive while it fades";
  ASSERT_TRUE(h.publish(std::make_unique<int>(3)));
  EXPECT_FALSE(h.take_keeping_previous()) << "no new object while the old one is held";
  ASSERT_TRUE(h.release_previous());
  ASSERT_TRUE(h.take_keeping_previous()) << "released: the waiting offer is taken, no publish needed";
  ASSERT_TRUE(h.release_previous()) << "a second slot holds it until the next publish reclaims both";
  EXPECT_EQ(*h.held(), 3);
  ASSERT_TRUE(h.publish(nullptr));
  ASSERT_TRUE(h.take_keeping_previous());
  EXPECT_EQ(h.held(), nullptr);
  EXPECT_EQ(*h.previous(), 3);
}

}  // namespace
}  // namespace knoblab::hapticd
