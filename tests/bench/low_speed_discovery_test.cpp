// Discovery on the second plant where the thesis model's blind spot is:
// friction that rises above its Coulomb level only very near zero speed
// (Stribeck velocities of real bearings, 0.01–0.1 rad/s).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "findings.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "two_body_plant.hpp"

namespace {

using knoblab::test::finding;
using knoblab::test::param;

using namespace knoblab;

// Coulomb 10 mN·m, a static excess of 3 mN·m falling off over 0.02 rad/s,
// torque noise 0.3 mN·m, through a stiff gripper. The swept sine passes
// 0.02 rad/s in a millisecond at each reversal, where its velocity cannot
// resolve the curve; a researcher after low-speed friction turns the knob
// slowly instead: legs of ±3° at speeds from 0.01 to 1 rad/s.
bench::TwoBodyConfig low_speed_stribeck() {
  bench::TwoBodyConfig c;
  c.knob.inertia = 5e-5;
  c.knob.coulomb_pos = c.knob.coulomb_neg = 10e-3;
  c.knob.viscous_pos = c.knob.viscous_neg = 0.5e-3;
  c.knob.static_excess = 3e-3;
  c.knob.stribeck_speed = 0.02;
  c.coupling.stiffness = std::numeric_limits<double>::infinity();
  c.camera.torque_noise_rms = 0.3e-3;
  c.camera.encoder_counts_per_rev = 0;  // an exact angle: see the test's comment
  c.stimulus.kind = bench::MotorStimulus::Kind::Triangle;
  c.stimulus.triangle = {0.05, 0.01, 1.0, 5, 20.0};
  c.seconds = 30.0;
  return c;
}

// Unfiltered: the Table 6 low-pass filters, made for the swept sine's
// channels, bend the slow legs' friction (v_s 0.057 rad/s with them), and
// the velocity comes from differences of an exact angle (a real encoder's
// counts would need smoothing first at 0.01 rad/s).
TEST(LowSpeedDiscovery, StribeckAtTwoHundredthsOfARadianPerSecondIsNamedWithItsVelocityOnASlowSweep) {
  const bench::TwoBodyRun run = bench::run_two_body(low_speed_stribeck());
  fit::PrepOptions raw;
  raw.filter = false;
  const discovery::DiscrepancyResult r = discovery::discover(fit::prepare(run.capture, raw));
  const discovery::Finding* f = finding(r, discovery::EffectId::Stribeck);
  ASSERT_NE(f, nullptr) << discovery::to_json(r);
  const double vs = param(*f, "stribeck_velocity_rad_s");
  EXPECT_GT(vs, 0.02 / 1.5) << f->explanation;
  EXPECT_LT(vs, 0.02 * 1.5) << f->explanation;
  EXPECT_NEAR(param(*f, "static_excess_Nm"), 3e-3, 0.5e-3) << f->explanation;
}

}  // namespace
