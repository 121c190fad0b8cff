// The library effects that are not knob torques: presliding hysteresis and
// endstops (knob terms), compliance (the coupling), time delay and
// saturation (the torque channel). Each: the spec, what the sensor reads with
// it in the plant, and bad parameters rejected with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "knoblab/model/effects.hpp"
#include "knoblab/sim/delay_line.hpp"
#include "knoblab/sim/library_effects.hpp"
#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"

using namespace knoblab;
using namespace knoblab::sim;

namespace {

constexpr double kPi = std::numbers::pi;

model::EffectSpec spec(const char* text) { return model::parse_effect_spec(text); }

// One ADC step of the torque channel, N·m.
double torque_lsb(const PlantConfig& c) {
  return c.torque_sensor.scale.to_torque(c.torque_sensor.adc.lsb());
}

// A light knob with Coulomb friction only (no stick band, no detents).
PlantConfig coulomb_knob(double C) {
  PlantConfig c = test::quiet({});
  c.knob.inertia.M = 1e-5;
  c.knob.friction = {C, 0.0, C, 0.0};
  return c;
}

// A step of torque on the knob at t0 (what holding it back would take).
class StepLoad final : public KnobEffect {
 public:
  StepLoad(double t0, double tau) : t0_(t0), tau_(tau) {}
  double torque(const KnobMotion&, double t) const override { return t >= t0_ ? tau_ : 0.0; }

 private:
  double t0_, tau_;
};

// A PD loop on the true motor state: no encoder steps in the command, so the
// sensor shows the knob's torques without the loop's limit cycle.
double smooth_command(const Plant& p, double theta_ref, double omega_ref) {
  return 300.0 * (theta_ref - p.state().motor_angle) + 1.0 * (omega_ref - p.state().motor_velocity);
}

std::string rejection(const char* text) {
  try {
    model::parse_effect_specs(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(OperatorEffects, BadParametersAreRejectedWithTheReason) {
  const std::pair<const char*, const char*> bad[] = {
      {"hysteresis:presliding_angle_rad=0", "presliding_angle_rad must be in (0, 0.1] rad"},
      {"hysteresis:presliding_angle_rad=0.5", "presliding_angle_rad must be in (0, 0.1] rad, not 0.5"},
      {"endstop:stiffness_Nm_per_rad=1", "needs position_rad"},
      {"endstop:position_rad=0.3", "needs stiffness_Nm_per_rad"},
      {"endstop:position_rad=0.3,stiffness_Nm_per_rad=1,damping_Nm_s_per_rad=-1",
       "damping_Nm_s_per_rad must be >= 0 N·m·s/rad (dissipative)"},
      {"compliance:zeta=0.1", "needs one of stiffness_Nm_per_rad, frequency_hz"},
      {"compliance:stiffness_Nm_per_rad=10,frequency_hz=50", "give stiffness_Nm_per_rad or frequency_hz, not both"},
      {"compliance:frequency_hz=50,damping_Nm_s_per_rad=0.01,zeta=0.1",
       "give damping_Nm_s_per_rad or zeta, not both"},
      {"compliance:frequency_hz=-5", "frequency_hz must be > 0 Hz"},
      {"time_delay:delay_s=-0.001", "torque behind the motion"},
      {"time_delay:delay_s=1", "delay_s must be in [0, 0.1] s"},
      {"saturation:limit_Nm=0", "limit_Nm must be > 0 N·m"},
      {"saturation", "needs limit_Nm"},
      {"backlash:width_rad=0.6", "width_rad must be in (0, 0.5] rad"},
  };
  for (const auto& [text, why] : bad) {
    const std::string what = rejection(text);
    EXPECT_NE(what.find(why), std::string::npos) << text << " → '" << what << "'";
  }
}

TEST(OperatorEffects, EachFoldsWhereItActs) {
  KnobParams k = *presets::knob("moderate-detents");
  EXPECT_TRUE(apply_to_knob(spec("hysteresis:presliding_angle_rad=0.002"), k));
  EXPECT_TRUE(apply_to_knob(spec("endstop:position_rad=0.5,stiffness_Nm_per_rad=2,damping_Nm_s_per_rad=0.01"), k));
  EXPECT_DOUBLE_EQ(k.presliding, 0.002);
  EXPECT_DOUBLE_EQ(k.walls.lo, -0.5);
  EXPECT_DOUBLE_EQ(k.walls.hi, 0.5);
  EXPECT_DOUBLE_EQ(k.walls.K, 2.0);
  EXPECT_DOUBLE_EQ(k.walls.B, 0.01);
  EXPECT_EQ(k.walls.limit, std::numeric_limits<double>::infinity()) << "a stop that climbs on";
  EXPECT_TRUE(check(k).empty());
  EXPECT_TRUE(apply_to_knob(spec("endstop:position_rad=0.5,stiffness_Nm_per_rad=2,max_torque_Nm=0.12"), k));
  EXPECT_DOUBLE_EQ(k.walls.limit, 0.12);
  EXPECT_DOUBLE_EQ(k.walls.torque(0.9, 0.0), 0.12) << "a wall that tops out";
  EXPECT_TRUE(check(k).empty());
  for (const char* rig : {"compliance:stiffness_Nm_per_rad=5", "time_delay:delay_s=0.001", "saturation:limit_Nm=0.01"}) {
    EXPECT_FALSE(apply_to_knob(spec(rig), k)) << rig;
    EXPECT_THROW(make_knob_effect(spec(rig)), std::invalid_argument) << rig;
  }

  PlantConfig c;
  c.knob = k;
  EXPECT_FALSE(apply_to_plant(spec("offset:offset_Nm=0.001"), c));
  EXPECT_FALSE(apply_to_plant(spec("hysteresis:presliding_angle_rad=0.002"), c));
  EXPECT_TRUE(apply_to_plant(spec("time_delay:delay_s=0.0015"), c));
  EXPECT_TRUE(apply_to_plant(spec("saturation:limit_Nm=0.012"), c));
  EXPECT_DOUBLE_EQ(c.torque_sensor.delay, 0.0015);
  EXPECT_DOUBLE_EQ(c.torque_sensor.saturation, 0.012);
  // Stiffness alone keeps the coupling's damping ratio: c scales with √k.
  const CouplingParams stiff = c.coupling;
  EXPECT_TRUE(apply_to_plant(spec("compliance:stiffness_Nm_per_rad=4"), c));
  EXPECT_DOUBLE_EQ(c.coupling.stiffness, 4.0);
  EXPECT_NEAR(c.coupling.damping, stiff.damping * std::sqrt(4.0 / stiff.stiffness), 1e-15);
  // A knob side without inertia cannot be tuned to a frequency.
  PlantConfig massless;
  massless.knob.inertia.M = 0.0;
  EXPECT_THROW(apply_to_plant(spec("compliance:frequency_hz=50"), massless), std::invalid_argument);
}

TEST(OperatorEffects, ThePlantRejectsSettingsOutOfRange) {
  // The same bounds when a config is built without the specs.
  const auto why = [](const PlantConfig& c) -> std::string {
    try {
      Plant p(c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  PlantConfig ok = coulomb_knob(0.001);
  ASSERT_EQ(why(ok), "");
  for (const double delay : {-1e-3, 0.5}) {
    PlantConfig c = ok;
    c.torque_sensor.delay = delay;
    EXPECT_NE(why(c).find("delay"), std::string::npos) << delay;
  }
  PlantConfig c = ok;
  c.knob.presliding = 0.5;
  EXPECT_NE(why(c).find("presliding"), std::string::npos);
}

TEST(OperatorEffects, DelayLineReadsTheSignalDelayLate) {
  // A ramp survives linear resampling exactly, at any push spacing.
  DelayLine d(0.00123, 1e-5);
  d.reset(0.0, 0.0);
  double t = 0.0;
  for (int n = 0; n < 2000; ++n) {
    t += n % 3 == 0 ? 7e-6 : 3.1e-6;
    d.push(t, 3.0 * t);
    if (t > 0.00123) {
      ASSERT_NEAR(d.read(t), 3.0 * (t - 0.00123), 1e-12) << t;
    } else {
      ASSERT_EQ(d.read(t), 0.0) << t;  // before the history: the reset value
    }
  }
}

TEST(OperatorEffects, TimeDelayShiftsTheTorqueChannelOnly) {
  // Two plants on the same commands, one with the torque channel 1 ms (ten
  // ticks) behind: the same motion, and its torque readings are the other's
  // ten ticks later (to the ADC's step).
  for (const auto& [delay, dt] : {std::pair{1e-3, 1e-4}, std::pair{2.5e-4, 5e-5}}) {
    PlantConfig c = test::quiet({});
    c.knob = *presets::knob("moderate-detents");
    Plant plain(c);
    ASSERT_TRUE(apply_to_plant(spec(("time_delay:delay_s=" + std::to_string(delay)).c_str()), c));
    Plant late(c);
    const auto lag = static_cast<std::size_t>(std::lround(delay / dt));
    test::PositionLoop loop;
    std::vector<double> plain_torque;
    int compared = 0;
    for (int n = 0; n < static_cast<int>(1.0 / dt); ++n) {
      const double t = n * dt;
      const double u = loop.command(plain, 0.5 * std::sin(2 * kPi * t), kPi * std::cos(2 * kPi * t), dt);
      plain.step(u, dt);
      late.step(u, dt);
      ASSERT_EQ(late.state().knob_angle, plain.state().knob_angle);
      plain_torque.push_back(plain.readings().torque);
      if (plain_torque.size() > lag) {
        ASSERT_NEAR(late.readings().torque, plain_torque[plain_torque.size() - 1 - lag], 1.01 * torque_lsb(c))
            << delay << " s at " << t;
        ++compared;
      } else {
        ASSERT_EQ(late.readings().torque, 0.0);  // nothing through the pipeline yet
      }
    }
    EXPECT_GT(compared, 5000);
  }
}

TEST(OperatorEffects, SaturationClipsTheSensorAtTheLimit) {
  // 8 mN·m of friction through a 5 mN·m sensor: flat tops at ±5, the true
  // torque below the limit.
  PlantConfig c = coulomb_knob(0.008);
  ASSERT_TRUE(apply_to_plant(spec("saturation:limit_Nm=0.005"), c));
  Plant p(c);
  test::PositionLoop loop;
  const double dt = 1e-4, lsb = torque_lsb(c);
  int clipped = 0, through = 0;
  for (int n = 0; n < 20000; ++n) {
    const double t = n * dt;
    p.step(loop.command(p, 0.3 * std::sin(2 * kPi * t), 0.6 * kPi * std::cos(2 * kPi * t), dt), dt);
    const double tau = p.state().coupling_torque, read = p.readings().torque;
    ASSERT_LE(std::abs(read), 0.005 + lsb) << t;
    if (std::abs(tau) > 0.005) {
      ASSERT_NEAR(read, std::copysign(0.005, tau), lsb) << t;
      ++clipped;
    } else {
      ASSERT_NEAR(read, tau, lsb) << t;
      ++through;
    }
  }
  EXPECT_GT(clipped, 15000);  // sliding: ±8 mN·m
  EXPECT_GT(through, 50);     // the reversals
}

TEST(OperatorEffects, EndstopPushesBackBeyondItsPosition) {
  // A frictionless knob held by a position loop at angles inside and beyond
  // stops at ±0.2 rad: beyond, the sensor reads the wall's K·overshoot.
  PlantConfig c = test::quiet({});
  c.knob.inertia.M = 1e-5;
  ASSERT_TRUE(apply_to_knob(spec("endstop:position_rad=0.2,stiffness_Nm_per_rad=0.5,damping_Nm_s_per_rad=0.002"), c.knob));
  Plant p(c);
  const double dt = 1e-4;
  for (const double target : {0.1, 0.3, -0.35, -0.15}) {
    for (int n = 0; n < 10000; ++n) p.step(smooth_command(p, target, 0.0), dt);  // 1 s to settle
    const double theta = p.state().knob_angle;
    const double over = std::abs(theta) > 0.2 ? theta - std::copysign(0.2, theta) : 0.0;
    EXPECT_NEAR(theta, target, 0.02);  // a P loop: the wall pushes it back a little
    EXPECT_NEAR(p.readings().torque, 0.5 * over, 2e-5) << target;
    if (std::abs(target) > 0.2) {
      EXPECT_GT(std::abs(p.readings().torque), 0.04) << target;
    }
  }
}

TEST(OperatorEffects, SofterCouplingRingsAtTheAskedFrequency) {
  // The motor held (a flywheel on it), a torque step on the knob: the knob
  // rings against the coupling at √(1 − ζ²)·f and the log decrement is ζ's.
  for (const double f : {40.0, 120.0}) {
    PlantConfig c = test::quiet({});
    c.knob.inertia.M = 2e-5;
    c.motor.extra_inertia = 10.0;
    ASSERT_TRUE(apply_to_plant(spec(("compliance:frequency_hz=" + std::to_string(f) + ",zeta=0.03").c_str()), c));
    EXPECT_NEAR(c.coupling.stiffness, 2e-5 * std::pow(2 * kPi * f, 2), 1e-9);
    Plant p(c);
    p.add_effect(std::make_unique<StepLoad>(0.01, 0.005));
    const double dt = 2e-5, settle = 0.005;  // the step's final coupling torque
    std::vector<double> up, peaks;  // upward zero crossings (s), |peaks| (N·m)
    double prev = 0.0, peak = 0.0;
    for (int n = 0; n < static_cast<int>(0.3 / dt); ++n) {
      p.step(0.0, dt);
      const double t = p.state().t, x = p.readings().torque - settle;
      if (t < 0.011) continue;
      if (prev < 0.0 && x >= 0.0) up.push_back(t - dt * x / (x - prev));
      if ((prev < 0.0) != (x < 0.0)) peaks.push_back(peak), peak = 0.0;
      peak = std::max(peak, std::abs(x));
      prev = x;
    }
    ASSERT_GE(up.size(), 6u) << f;
    const double period = (up[5] - up[0]) / 5.0;
    EXPECT_NEAR(1.0 / period, f * std::sqrt(1.0 - 0.03 * 0.03), 0.005 * f) << f;
    // Half-cycle peaks fall by exp(−π·ζ/√(1−ζ²)); from the second on (the
    // first is cut short by where the record starts).
    ASSERT_GE(peaks.size(), 7u);
    const double zeta = std::log(peaks[2] / peaks[6]) / (4.0 * kPi);
    EXPECT_NEAR(zeta, 0.03, 0.006) << f;
  }
}

TEST(OperatorEffects, HysteresisTurnsFrictionOverWithinThePreslidingAngle) {
  // Coulomb 3 mN·m with Dahl presliding of 2 mrad, driven ±50 mrad: after
  // each reversal the sensor reads C·z, z = ±(1 − 2·exp(−δ/θ_p)) over the
  // travel δ since the reversal; it crosses zero at δ = θ_p·ln 2, and the
  // loop's area is 4C·(A − θ_p) instead of Coulomb's 4C·A.
  const double C = 0.003, theta_p = 0.002, A = 0.05, dt = 1e-4, w = 2 * kPi * 0.5;
  PlantConfig c = coulomb_knob(C);
  ASSERT_TRUE(apply_to_knob(spec("hysteresis:presliding_angle_rad=0.002"), c.knob));
  Plant p(c);
  model::DahlFriction dahl;
  dahl.presliding = theta_p;
  double last = p.state().knob_angle, turn = last, area = 0.0, prev_read = 0.0;
  std::vector<double> crossings;  // travel from the reversal to the sign change
  int compared = 0;
  for (int n = 0; n < 60000; ++n) {
    const double t = n * dt;
    p.step(smooth_command(p, A * std::sin(w * t), A * w * std::cos(w * t)), dt);
    const double theta = p.state().knob_angle, read = p.readings().torque;
    dahl.update(theta - last);
    const bool reversed = (theta - last) * (last - turn) < 0.0;  // direction changed
    if (reversed || n == 0) turn = last;
    if (t > 2.0) {  // two full cycles from the start (the loop's own transient)
      // The loop holds the knob within the coupling's twist of the motor, so
      // the sensor reads friction (plus M·α, under 10 µN·m here).
      ASSERT_NEAR(read, C * dahl.z, 3e-5) << t;
      ++compared;
      if (t <= 4.0) area += read * (theta - last);
      if ((prev_read < 0.0) != (read < 0.0)) crossings.push_back(std::abs(theta - turn));
    }
    prev_read = read;
    last = theta;
  }
  EXPECT_GT(compared, 30000);
  ASSERT_GE(crossings.size(), 4u);
  for (const double x : crossings) EXPECT_NEAR(x, theta_p * std::log(2.0), 0.1 * theta_p);
  EXPECT_NEAR(area, 4 * C * (A - theta_p), 0.02 * 4 * C * A);  // one cycle, t = 2 … 4 s
  EXPECT_GT(area, 0.0);  // dissipative
}

TEST(OperatorEffects, HysteresisLeavesTheStickBandHoldingTheKnob) {
  // With a Karnopp band (static 6 mN·m over Coulomb 3) the knob still sticks
  // at each reversal (z stands with it: no travel); after breakaway the
  // bristles turn over within the presliding angle of travel, and the cycle
  // dissipates at least the Dahl loop.
  const double C = 0.003, theta_p = 0.002, A = 0.05, dt = 1e-4, w = 2 * kPi * 0.5;
  PlantConfig c = coulomb_knob(C);
  c.knob.stick = {0.01, 0.006, 0.006};
  ASSERT_TRUE(apply_to_knob(spec("hysteresis:presliding_angle_rad=0.002"), c.knob));
  Plant p(c);
  double last = p.state().knob_angle, area = 0.0, freed_at = std::nan("");
  int sticks = 0, crossings = 0;
  double prev_read = 0.0;
  bool was_stuck = false;
  for (int n = 0; n < 40000; ++n) {
    const double t = n * dt;
    p.step(smooth_command(p, A * std::sin(w * t), A * w * std::cos(w * t)), dt);
    const PlantState& s = p.state();
    const double read = p.readings().torque;
    if (s.stuck) {
      sticks += was_stuck ? 0 : 1;
      freed_at = s.knob_angle;
    }
    was_stuck = s.stuck;
    if (t > 2.0) {
      area += read * (s.knob_angle - last);
      // After breakaway (the reading drops from +D to −C: the bristles still
      // lean the old way) it turns towards the motion once, θ_p·ln 2 on.
      const double dir = s.knob_velocity > 0 ? 1.0 : -1.0;
      if (!s.stuck && prev_read * dir < 0.0 && read * dir >= 0.0 && !std::isnan(freed_at)) {
        EXPECT_NEAR(std::abs(s.knob_angle - freed_at), theta_p * std::log(2.0), 0.15 * theta_p) << t;
        ++crossings;
      }
    }
    prev_read = read;
    last = s.knob_angle;
  }
  EXPECT_GE(sticks, 4);  // two cycles
  EXPECT_GE(crossings, 2);  // the two reversals after t = 2 s
  EXPECT_GT(area, 0.98 * 4 * C * (A - theta_p));  // one cycle, t = 2 … 4 s
}
