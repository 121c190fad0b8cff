// The effect library's terms and operators (knoblab/model/effects.hpp) and
// the discrepancy ids.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knoblab/discovery/effects.hpp"
#include "knoblab/model/effects.hpp"

namespace knoblab {
namespace {

TEST(Effects, IdsRoundTripThroughTheirNames) {
  for (const discovery::EffectId id : discovery::kAllEffects) {
    EXPECT_EQ(discovery::parse_effect(discovery::effect_name(id)), id);
  }
  EXPECT_EQ(discovery::parse_effect("stribeck"), discovery::EffectId::Stribeck);
  EXPECT_FALSE(discovery::parse_effect("cogging").has_value());
}

TEST(Effects, StribeckExceedsCoulombOnlyNearZeroSpeed) {
  const model::Stribeck<double> s{0.002, 0.1};
  EXPECT_DOUBLE_EQ(s.torque(0.0), 0.0);
  EXPECT_NEAR(s.torque(1e-4), 0.002, 1e-8);
  EXPECT_NEAR(s.torque(-1e-4), -0.002, 1e-8);
  EXPECT_NEAR(s.torque(0.1), 0.002 * std::exp(-1.0), 1e-12);
  EXPECT_LT(std::abs(s.torque(0.5)), 1e-12 + 0.002 * std::exp(-25.0));
}

TEST(Effects, PowerDampingAndPositionFrictionFollowTheVelocitySign) {
  const model::PowerDamping<double> q{0.01, 2.0};
  EXPECT_NEAR(q.torque(3.0), 0.09, 1e-12);
  EXPECT_NEAR(q.torque(-3.0), -0.09, 1e-12);
  const model::PositionFriction<double> f{0.001, 0.5, 0.0};
  EXPECT_NEAR(f.torque(std::numbers::pi / 4, 1.0), 0.001, 1e-12);   // sin(π/2)
  EXPECT_NEAR(f.torque(std::numbers::pi / 4, -1.0), -0.001, 1e-12);
}

TEST(Effects, BacklashPlayTakesUpTheWidthAtEachReversal) {
  model::Backlash b;
  b.width = 0.01;
  b.reset(0.0);
  // Forward: the drive takes up half the play before it pushes.
  EXPECT_DOUBLE_EQ(b.update(0.004), 0.0);
  EXPECT_FALSE(b.contact);
  EXPECT_NEAR(b.update(0.02), 0.015, 1e-15);
  EXPECT_TRUE(b.contact);
  // Reverse: the knob stays while the drive crosses the whole play.
  EXPECT_NEAR(b.update(0.012), 0.015, 1e-15);
  EXPECT_FALSE(b.contact);
  EXPECT_NEAR(b.update(0.0), 0.005, 1e-15);
  EXPECT_TRUE(b.contact);
}

TEST(Effects, DahlStateTurnsOverWithinAFewPreslidingAngles) {
  model::DahlFriction h;
  h.presliding = 1e-3;
  h.reset(-1.0);
  double z = 0.0;
  for (int k = 0; k < 10; ++k) z = h.update(1e-4);  // 1 mrad forward
  EXPECT_NEAR(z, 1.0 - 2.0 * std::exp(-1.0), 1e-12);
  for (int k = 0; k < 100; ++k) z = h.update(1e-4);
  EXPECT_NEAR(z, 1.0, 1e-4);
  EXPECT_DOUBLE_EQ(model::saturate(0.3, 0.2), 0.2);
  EXPECT_DOUBLE_EQ(model::saturate(-0.3, 0.2), -0.2);
}

}  // namespace
}  // namespace knoblab
