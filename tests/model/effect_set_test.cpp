// The renderable effects (effect_set.hpp) inside the rendering model: each
// the library's own term, the position ones held by the stick band.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "knoblab/model/effect_set.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::model {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

EffectSet<double> some_effects() {
  EffectSet<double> e;
  e.offset.tau0 = 0.001;
  e.gravity = {0.004, 0.3};
  e.spring.K = 0.02;
  e.spring.theta0 = 0.1;
  e.periodic[0].A = 0.002;
  e.periodic[0].P = 0.05;
  e.periodic[0].S = 0.7;
  e.periodic_count = 1;
  e.stribeck = {0.003, 0.2};
  e.damping = {0.001, 2.0};
  e.walls = {-1.0, 1.0, 2.0, 0.01};
  return e;
}

TEST(EffectSet, SumsTheLibraryTermsItHolds) {
  const EffectSet<double> e = some_effects();
  const double theta = 0.4, omega = 0.5;
  const double held = 0.001 + 0.004 * std::sin(theta + 0.3) + 0.02 * (theta - 0.1) +
                      0.002 * std::sin(theta / 0.05 + 0.7);
  EXPECT_NEAR(e.held(theta, omega), held, 1e-15);
  EXPECT_NEAR(e.sliding(omega), 0.003 * std::exp(-(0.5 / 0.2) * (0.5 / 0.2)) + 0.001 * 0.25, 1e-15);
  // A wall adds only beyond its position.
  EXPECT_NEAR(e.held(1.2, omega) - e.held(1.2, 0.0), 0.01 * omega, 1e-15);
}

TEST(EffectSet, ScaledToAFractionScalesEveryTermAndToZeroLeavesNone) {
  EffectSet<double> e = some_effects();
  for (const double limit : {kInfinity, 0.15}) {  // a wall that climbs on, and one that tops out
    e.walls.limit = limit;
    const EffectSet<double> half = e.scaled(0.5), none = e.scaled(0.0);
    for (const double theta : {-1.3, 0.2, 1.1, 1.2}) {
      EXPECT_NEAR(half.held(theta, 0.3), 0.5 * e.held(theta, 0.3), 1e-15) << theta;
      EXPECT_EQ(none.held(theta, 0.3), 0.0) << theta;
    }
    EXPECT_NEAR(half.sliding(-0.4), 0.5 * e.sliding(-0.4), 1e-15);
    EXPECT_EQ(none.sliding(-0.4), 0.0);
  }
}

TEST(EffectSet, DetentShapeBecomesTheDetentsHarmonics) {
  EffectSet<double> e;
  e.detent_a[1] = 0.003;  // a3
  e.detent_b[0] = -0.001;  // b2
  Detents<double> d;
  d.A = 0.01;
  d.P = 1.0 / 12.0;
  e.shape_detents(d);
  const double phi = 0.2 * 12.0;
  EXPECT_NEAR(d.torque(0.2), 0.01 * std::sin(phi) - 0.001 * std::cos(2 * phi) + 0.003 * std::sin(3 * phi), 1e-15);
}

TEST(RenderModel, EffectsAddToEquation14OutsideTheStickBand) {
  RenderModel<double> m;
  m.B_vel = 0.3;
  m.detents.A = 0.01;
  m.detents.P = 1.0 / 12.0;
  m.stick_enabled = true;
  m.stick = {0.01, 0.02, 0.03};
  m.effects = some_effects();
  const Kinematics<double> k{0.4, 0.5, 0.0};
  EXPECT_NEAR(m.torque(k), 0.3 * 0.5 + 0.01 * std::sin(0.4 * 12.0) + m.effects.held(0.4, 0.5) + m.effects.sliding(0.5),
              1e-15);
}

TEST(RenderModel, StickBandHoldsAgainstTheEffectsPositionTorques) {
  RenderModel<double> m;
  m.stick_enabled = true;
  m.stick = {0.01, 0.02, 0.02};
  m.effects.gravity = {0.05, 0.0};  // beyond the band's 20 mN·m at θ = π/2
  const Kinematics<double> k{std::acos(0.0), 0.0, 0.0};
  // The hand applies nothing: friction holds what it can of the 50 mN·m
  // gravity pull, and the knob feels the rest, not the gravity alone.
  EXPECT_NEAR(m.torque(k, 0.0), 0.05 - 0.02, 1e-15);
  // Stribeck and power damping are sliding friction: nothing inside the band.
  m.effects.gravity = {};
  m.effects.stribeck = {0.01, 1.0};
  EXPECT_NEAR(m.torque({0.0, 0.005, 0.0}, 0.0), 0.0, 1e-15);
}

}  // namespace
}  // namespace knoblab::model
