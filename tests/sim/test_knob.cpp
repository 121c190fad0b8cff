// The knob side: Karnopp stick/breakaway, detents seen through the sensor,
// the knob's own dynamics and the effect seam.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "helpers.hpp"
#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"

using namespace knoblab::sim;

namespace {

constexpr double kNmPerVolt = 0.181 / 12.0;  // current mode

// Ramps the motor torque linearly from `from` to `to` (N·m) over `seconds`,
// calling check(plant) after each 10 kHz tick.
template <typename F>
void ramp(Plant& p, double from, double to, double seconds, F check) {
  const double dt = 1e-4;
  const int n = static_cast<int>(std::lround(seconds / dt));
  for (int i = 1; i <= n; ++i) {
    p.step((from + (to - from) * i / n) / kNmPerVolt, dt);
    check(p);
  }
}

}  // namespace

TEST(Knob, StuckBelowStaticFrictionBreaksAwayAbove) {
  PlantConfig c = test::quiet({});
  c.knob = *presets::knob("high-inertia");  // D = 17 mN·m, C = 3.8 mN·m
  Plant p(c);
  ramp(p, 0.0, 0.012, 0.1, [](const Plant& q) {
    ASSERT_TRUE(q.state().stuck);
    ASSERT_EQ(q.state().knob_velocity, 0.0);
    ASSERT_EQ(q.state().knob_angle, 0.0);
  });
  ramp(p, 0.012, 0.012, 0.5, [](const Plant& q) { ASSERT_TRUE(q.state().stuck); });
  // The sensor reads the torque that holds it.
  EXPECT_NEAR(p.readings().torque, 0.012, 0.05e-3);

  double last_stuck_torque = 0.0;
  ramp(p, 0.012, 0.025, 0.2, [&](const Plant& q) {
    if (q.state().stuck) last_stuck_torque = q.state().coupling_torque;
  });
  EXPECT_NEAR(last_stuck_torque, 0.017, 0.2e-3);  // broke away at D_pos
  EXPECT_FALSE(p.state().stuck);
  EXPECT_GT(p.state().knob_velocity, c.knob.stick.dv);
  EXPECT_GT(p.state().knob_angle, 0.01);
}

TEST(Knob, StaticLimitsAreAsymmetric) {
  PlantConfig c = test::quiet({});
  c.knob.inertia.M = 5e-5;
  c.knob.friction = {0.002, 0.0005, 0.002, 0.0005};
  c.knob.stick = {0.01, 0.005, 0.020};  // dv, D_neg, D_pos
  Plant p(c);
  ramp(p, 0.0, 0.015, 0.2, [](const Plant& q) { ASSERT_TRUE(q.state().stuck); });
  ramp(p, 0.015, 0.0, 0.1, [](const Plant& q) { ASSERT_TRUE(q.state().stuck); });
  ramp(p, 0.0, -0.004, 0.1, [](const Plant& q) { ASSERT_TRUE(q.state().stuck); });
  ramp(p, -0.004, -0.008, 0.2, [](const Plant&) {});
  EXPECT_FALSE(p.state().stuck);
  EXPECT_LT(p.state().knob_velocity, -c.knob.stick.dv);
}

TEST(Knob, SlidingKnobComesToRestAndSticks) {
  PlantConfig c = test::quiet({});
  c.knob = *presets::knob("high-friction");  // C = 50 mN·m, D = 150 mN·m
  Plant p(c);
  ramp(p, 0.0, 0.17, 0.05, [](const Plant&) {});
  ramp(p, 0.17, 0.17, 0.05, [](const Plant&) {});
  ASSERT_FALSE(p.state().stuck);
  ASSERT_GT(p.state().knob_velocity, 1.0);
  // 30 mN·m is below C: the knob slows down, stops and stays stopped.
  ramp(p, 0.03, 0.03, 0.2, [](const Plant&) {});
  EXPECT_TRUE(p.state().stuck);
  EXPECT_EQ(p.state().knob_velocity, 0.0);
  EXPECT_NEAR(p.readings().torque, 0.03, 0.1e-3);
}

TEST(Knob, DetentsSeenByTheSensorMatchModel) {
  PlantConfig c;  // with sensor noise
  c.knob = *presets::knob("moderate-detents");
  Plant p(c);
  test::PositionLoop loop;
  const double dt = 1e-4, w = 1.0;  // drive at 1 rad/s
  const auto& d = c.knob.detents;
  std::vector<double> theta, tau;
  double t = 0.0;
  while (t < 0.3 + 2 * std::numbers::pi / w) {
    p.step(loop.command(p, w * t, w, dt), dt);
    t += dt;
    const double th = p.encoder_scale().to_angle(p.readings().encoder_counts);
    if (t > 0.3) {  // past the start-up transient: exactly one revolution
      theta.push_back(th);
      tau.push_back(p.readings().torque);
    }
  }
  // Least squares τ ≈ c0 + a·sin(θ/P) + b·cos(θ/P).
  double s[3][3] = {}, r[3] = {};
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double f[3] = {1.0, std::sin(theta[i] / d.P), std::cos(theta[i] / d.P)};
    for (int j = 0; j < 3; ++j) {
      r[j] += f[j] * tau[i];
      for (int k = 0; k < 3; ++k) s[j][k] += f[j] * f[k];
    }
  }
  // The basis is near-orthogonal over whole periods: solve by Cramer's rule.
  auto det3 = [](double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double D = det3(s);
  double x[3];
  for (int j = 0; j < 3; ++j) {
    double m[3][3];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) m[a][b] = b == j ? r[a] : s[a][b];
    x[j] = det3(m) / D;
  }
  // A·sin(θ/P + S) = A·cos S·sin(θ/P) + A·sin S·cos(θ/P)
  EXPECT_NEAR(x[1], d.A * std::cos(d.S), 0.4e-3);
  EXPECT_NEAR(x[2], d.A * std::sin(d.S), 0.4e-3);
  EXPECT_NEAR(std::hypot(x[1], x[2]), std::abs(d.A), 0.05 * std::abs(d.A));
  // Offset: sliding friction at 1 rad/s, C_pos + B_pos·1.
  EXPECT_NEAR(x[0], c.knob.friction.C_pos + c.knob.friction.B_pos * w, 0.3e-3);

  // Shape: the residual is small, and there are 12 detents in the turn.
  double res2 = 0.0;
  int peaks = 0, side = 0;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double model = x[0] + d.torque(theta[i]);
    res2 += (tau[i] - model) * (tau[i] - model);
    const double v = tau[i] - x[0];
    if (v > 0.3 * std::abs(d.A) && side <= 0) {
      ++peaks;
      side = 1;
    } else if (v < -0.3 * std::abs(d.A)) {
      side = -1;
    }
  }
  EXPECT_LT(std::sqrt(res2 / static_cast<double>(theta.size())), 0.5e-3);
  EXPECT_EQ(peaks, 12);
}

TEST(Knob, SensorReadsEq6TorqueOfTheTrueMotion) {
  // Thesis capture (Eq. 8, Table 3 spatial row, 5 kHz) under a PD loop: while
  // the knob slides, the coupling torque is Eq. 6 of the knob's true motion —
  // the sign convention and the terms are the model's own.
  for (const char* id : {"high-inertia", "moderate-detents", "study2-high-friction"}) {
    SCOPED_TRACE(id);
    PlantConfig c;
    c.knob = *presets::knob(id);
    Plant p(c);
    const auto model = thesis_model(c.knob);
    test::PositionLoop loop;
    const double dt = 2e-4;
    int sliding = 0;
    for (int k = 0; k < 15000; ++k) {
      const double t = k * dt, x = 1.5 * t / 3.0;
      const double phase = std::numbers::pi / 1.5 * x * x;
      const double ref = std::sin(phase);
      const double wref = 2 * std::numbers::pi * x / 3.0 * std::cos(phase);
      p.step(loop.command(p, ref, wref, dt), dt);
      const PlantState& s = p.state();
      ASSERT_LT(std::abs(ref - s.knob_angle), 0.01);  // it does follow the sweep
      if (std::abs(s.knob_velocity) <= 1.5 * c.knob.stick.dv) continue;  // Eq. 7, not Eq. 6
      ++sliding;
      const double tau = model.torque({s.knob_angle, s.knob_velocity, s.knob_accel});
      ASSERT_NEAR(s.coupling_torque, tau, 1e-5) << t;
    }
    EXPECT_GT(sliding, 13000);
  }
}

TEST(Knob, SpringOscillatesAtItsNaturalFrequency) {
  PlantConfig c = test::quiet({});
  c.knob.inertia.M = 1e-4;
  c.knob.spring.K = 0.05;  // N·m/rad
  c.initial_angle = 0.2;   // released from 0.2 rad, motor side with it
  Plant p(c);
  // The current-mode motor (i = 0) rides along: J = M + J_rotor.
  const double period = 2 * std::numbers::pi * std::sqrt((1e-4 + 1e-6) / 0.05);  // 0.283 s
  std::vector<double> ups;
  double prev = p.state().knob_angle;
  for (int n = 0; n < 20000; ++n) {
    p.step(0.0, 1e-4);
    const double th = p.state().knob_angle;
    if (prev < 0.0 && th >= 0.0) ups.push_back(p.state().t);
    prev = th;
  }
  ASSERT_GE(ups.size(), 5u);
  const double measured = (ups.back() - ups.front()) / static_cast<double>(ups.size() - 1);
  EXPECT_NEAR(measured, period, 1e-3 * period);
}

namespace {

// A constant torque bias, as the simplest possible effect.
class Bias : public KnobEffect {
 public:
  explicit Bias(double tau, int* advances) : tau_(tau), advances_(advances) {}
  double torque(const KnobMotion&, double) const override { return tau_; }
  void advance(const KnobMotion&, double, double) override { ++*advances_; }

 private:
  double tau_;
  int* advances_;
};

}  // namespace

TEST(Knob, EffectsAddTorqueWithTheTermsSignConvention) {
  PlantConfig c = test::quiet({});
  c.knob.inertia.M = 1e-4;
  Plant p(c);
  int advances = 0;
  p.add_effect(std::make_unique<Bias>(0.002, &advances));
  for (int n = 0; n < 1000; ++n) p.step(0.0, 1e-4);  // 0.1 s
  // "Torque needed to move the knob" = +2 mN·m: the knob runs backwards.
  EXPECT_NEAR(p.state().knob_velocity, -0.002 / (1e-4 + 1e-6) * 0.1, 0.01 * 1.98);
  EXPECT_EQ(advances, 1000 * 10);
}

TEST(Knob, InvalidKnobIsRejected) {
  PlantConfig c;
  c.knob.inertia.M = 0.0;  // nothing on the knob side
  EXPECT_THROW(Plant{c}, std::invalid_argument);
  c.knob.inertia.M = 1e-5;
  c.knob.friction.B_pos = -1e-3;  // active "friction"
  EXPECT_THROW(Plant{c}, std::invalid_argument);
  c.knob.friction.B_pos = 0.0;
  c.coupling.gripper_inertia = 2e-6;
  EXPECT_NO_THROW(Plant{c});
}
