// The existing torque terms (terms.hpp, models.hpp) against the thesis.
#include <gtest/gtest.h>

#include <cmath>

#include "knoblab/model/models.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::model {
namespace {

// Thesis Eq. 10 through the parameter vector, in kThesisParamNames order.
ThesisModel<double> eq10() {
  const double p[kThesisParamCount] = {0.4, 1.5, 1.0, 2.0, 1.5, 1.0, 0.2, 0.9};
  return ThesisModel<double>::from_params(p);
}

TEST(ThesisModel, Equation10Values) {
  const ThesisModel<double> m = eq10();
  // (θ, θ̇, θ̈) → acc, vel, pos, total; worked by hand from Eq. 10.
  struct Row { double th, om, al, acc, vel, pos, total; };
  const Row rows[] = {
      {0.5, 2.0, -3.0, -1.2, 5.0, -0.255541102026831, 3.54445889797317},
      {-0.3, -0.7, 1.2, 0.48, -2.2, -0.564642473395035, -2.28464247339504},
      {1.0, 0.0, 0.0, 0.0, 0.0, -0.373876664830236, -0.373876664830236},
  };
  for (const Row& r : rows) {
    const TorqueParts<double> parts = m.parts({r.th, r.om, r.al});
    EXPECT_NEAR(parts.acc, r.acc, 1e-12);
    EXPECT_NEAR(parts.vel, r.vel, 1e-12);
    EXPECT_NEAR(parts.pos, r.pos, 1e-12);
    EXPECT_NEAR(m.torque({r.th, r.om, r.al}), r.total, 1e-12);
  }
}

TEST(ThesisModel, PartsSumToTotal) {
  const ThesisModel<double> m = eq10();
  for (double t = -2.0; t < 2.0; t += 0.37) {
    const Kinematics<double> k{t, std::sin(3 * t), std::cos(5 * t)};
    const TorqueParts<double> parts = m.parts(k);
    EXPECT_DOUBLE_EQ(parts.acc + parts.vel + parts.pos, m.torque(k));
  }
}

TEST(ThesisModel, ParamNamesFollowTheEnum) {
  EXPECT_EQ(kThesisParamNames[kM_acc], "M_acc");
  EXPECT_EQ(kThesisParamNames[kP_pos], "P_pos");
  EXPECT_EQ(kThesisParamNames[kS_pos], "S_pos");
  const ThesisModel<double> m = eq10();
  EXPECT_EQ(m.friction.C_neg, 1.5);
  EXPECT_EQ(m.friction.B_pos, 1.5);
  EXPECT_EQ(m.detents.P, 0.2);
}

TEST(CoulombViscous, IsDissipativeAndAsymmetric) {
  const CoulombViscous<double> f{1.5, 1.0, 2.0, 1.5};
  EXPECT_EQ(f.torque(0.0), 0.0);
  EXPECT_DOUBLE_EQ(f.torque(1e-9), 2.0 + 1.5e-9);
  EXPECT_DOUBLE_EQ(f.torque(-1e-9), -1.5 - 1e-9);
  for (double w = -3.0; w <= 3.0; w += 0.25) EXPECT_GE(f.torque(w) * w, 0.0);
}

TEST(CoulombViscous, DahlFormTakesTheCoulombPartFromTheFrictionState) {
  const CoulombViscous<double> f{1.5, 1.0, 2.0, 1.5};
  // Fully turned over (z = ±1) it is the sliding law.
  EXPECT_DOUBLE_EQ(f.torque_dahl(0.5, 1.0), f.torque(0.5));
  EXPECT_DOUBLE_EQ(f.torque_dahl(-0.5, -1.0), f.torque(-0.5));
  // Just after a reversal (moving back, z still +0.5): half of C_pos,
  // against the new motion's viscous part.
  EXPECT_DOUBLE_EQ(f.torque_dahl(-0.5, 0.5), 0.5 * 2.0 + 1.0 * -0.5);
  EXPECT_DOUBLE_EQ(f.torque_dahl(0.0, -0.25), -0.25 * 1.5);
}

TEST(KarnoppStick, InsideBandHoldsUpToStaticLimits) {
  const CoulombViscous<double> sliding{0.01, 0.002, 0.012, 0.003};
  const KarnoppStick<double> stick{0.01, 0.15, 0.2};
  EXPECT_TRUE(stick.sticking(0.005));
  EXPECT_TRUE(stick.sticking(-0.009));
  EXPECT_DOUBLE_EQ(stick.torque(0.005, 0.1, sliding), 0.1);
  EXPECT_DOUBLE_EQ(stick.torque(-0.005, -0.1, sliding), -0.1);
  EXPECT_DOUBLE_EQ(stick.torque(0.005, 0.5, sliding), 0.2);
  EXPECT_DOUBLE_EQ(stick.torque(-0.005, -0.5, sliding), -0.15);
}

TEST(KarnoppStick, OutsideBandSlides) {
  const CoulombViscous<double> sliding{0.01, 0.002, 0.012, 0.003};
  const KarnoppStick<double> stick{0.01, 0.15, 0.2};
  EXPECT_FALSE(stick.sticking(0.01));  // the band is open
  EXPECT_DOUBLE_EQ(stick.torque(0.5, 0.1, sliding), sliding.torque(0.5));
  EXPECT_DOUBLE_EQ(stick.torque(-0.5, 0.1, sliding), sliding.torque(-0.5));
  const KarnoppStick<double> none{0.0, 1.0, 1.0};
  EXPECT_FALSE(none.sticking(0.0));
}

TEST(Detents, SineWithHarmonics) {
  Detents<double> d;
  d.A = 0.8;
  d.P = 1.0 / 12.0;
  d.S = 0.3;
  d.a[2] = 0.2;
  d.b[3] = -0.1;
  d.a[4] = 0.5;  // beyond `harmonics`: not part of the shape
  d.harmonics = 3;
  EXPECT_DOUBLE_EQ(cycles_per_rev(d), 12.0);
  for (double th = -1.0; th < 1.0; th += 0.093) {
    const double phi = 12.0 * th + 0.3;
    EXPECT_NEAR(d.torque(th), 0.8 * std::sin(phi) + 0.2 * std::sin(2 * phi) - 0.1 * std::cos(3 * phi),
                1e-12);
  }
  // One revolution holds exactly 12 periods.
  EXPECT_NEAR(d.torque(0.4 + 2 * std::acos(-1.0)), d.torque(0.4), 1e-12);
}

TEST(SpringAndWalls, Basics) {
  const Spring<double> s{2.0, 0.5, 1.0};
  EXPECT_DOUBLE_EQ(s.torque(1.5), 2.0 + 1.0);
  EXPECT_DOUBLE_EQ(s.torque(0.5), 0.0);
  const Walls<double> w{-1.0, 1.0, 10.0, 0.5};
  EXPECT_EQ(w.torque(0.0, 3.0), 0.0);
  EXPECT_DOUBLE_EQ(w.torque(1.1, 2.0), 10.0 * 0.1 + 1.0);
  EXPECT_DOUBLE_EQ(w.torque(-1.2, -2.0), -2.0 - 1.0);
  // A wall that tops out (a rendered one): its spring holds at ±limit, the
  // damper still acts on top.
  Walls<double> level = w;
  level.limit = 1.5;
  EXPECT_DOUBLE_EQ(level.torque(1.1, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(level.torque(1.4, 2.0), 1.5 + 1.0);
  EXPECT_DOUBLE_EQ(level.torque(-3.0, 0.0), -1.5);
  EXPECT_EQ(level.torque(0.9, 2.0), 0.0);
}

TEST(RenderModel, Equation14WithoutStick) {
  RenderModel<double> m;
  m.inertia.M = 0.05;
  m.B_vel = 0.3;
  m.detents.A = 0.01;
  m.detents.P = 1.0 / 30.0;
  const Kinematics<double> k{0.2, -1.5, 4.0};
  EXPECT_NEAR(m.torque(k), 0.05 * 4.0 + 0.3 * -1.5 + 0.01 * std::sin(0.2 * 30.0), 1e-14);
  EXPECT_EQ(m.sliding().C_pos, 0.0);
}

TEST(RenderModel, StickBandHoldsAgainstTheHandUpToTheStaticLimit) {
  RenderModel<double> m;
  m.inertia.M = 0.05;
  m.B_vel = 0.3;
  m.detents.A = 0.01;
  m.detents.P = 1.0 / 12.0;
  m.stick_enabled = true;
  m.stick = {0.01, 0.02, 0.03};
  const Kinematics<double> k{0.1, 0.001, 0.5};
  const double pos = 0.01 * std::sin(0.1 * 12.0), acc = 0.05 * 0.5;
  // A gentle push is fully resisted: the knob renders exactly what the hand applies.
  EXPECT_NEAR(m.torque(k, pos + acc + 0.015), pos + acc + 0.015, 1e-14);
  // A hard push breaks through: friction saturates at D_pos.
  EXPECT_NEAR(m.torque(k, pos + acc + 0.5), pos + acc + 0.03, 1e-14);
  EXPECT_NEAR(m.torque(k, pos + acc - 0.5), pos + acc - 0.02, 1e-14);
  // Outside the band the sliding law applies whatever the hand does.
  const Kinematics<double> moving{0.1, 0.5, 0.5};
  EXPECT_NEAR(m.torque(moving, 9.0), m.torque(moving, -9.0), 1e-14);
}

}  // namespace
}  // namespace knoblab::model
