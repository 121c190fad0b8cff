// The effect library on the simulated knob: specs, folding into the knob,
// the KnobEffects' torques and what the sensor reads with one in the plant.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <numbers>
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "helpers.hpp"
#include "knoblab/model/effects.hpp"
#include "knoblab/sim/library_effects.hpp"
#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"

using namespace knoblab;
using namespace knoblab::sim;

TEST(LibraryEffects, SpecsParseAndPrintBack) {
  const auto specs = model::parse_effect_specs(
      "stribeck:static_excess_Nm=0.002,stribeck_velocity_rad_s=0.1;gravity:amplitude_Nm=3e-3");
  ASSERT_EQ(specs.size(), 2u);
  EXPECT_EQ(specs[0].id(), "stribeck");
  EXPECT_DOUBLE_EQ(specs[0].value("static_excess_Nm"), 0.002);
  EXPECT_DOUBLE_EQ(specs[0].value("stribeck_velocity_rad_s"), 0.1);
  EXPECT_EQ(specs[1].value("amplitude_Nm"), 3e-3);
  EXPECT_EQ(specs[1].value("phase_rad"), 0.0);  // the table's default
  EXPECT_EQ(model::parse_effect_spec(specs[0].text()).params, specs[0].params);
}

// Named without the parameter that gives it a size, an effect would be zero.
TEST(LibraryEffects, AnEffectWithoutItsSizeIsRefusedSayingWhichParameterItNeeds) {
  const auto why = [](const char* text) {
    try {
      model::parse_effect_specs(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(why("stribeck").find("effect 'stribeck' needs static_excess_Nm: without it the effect is zero "
                                 "(its parameters: static_excess_Nm, stribeck_velocity_rad_s; "
                                 "e.g. 'stribeck:static_excess_Nm=…')"),
            std::string::npos)
      << why("stribeck");
  EXPECT_NE(why("spring:centre_rad=0.1").find("needs one of stiffness_Nm_per_rad, cubic_Nm_per_rad3"),
            std::string::npos)
      << why("spring:centre_rad=0.1");
  EXPECT_NE(why("offset").find("needs offset_Nm"), std::string::npos);
  EXPECT_NE(why("cogging:amplitude_Nm=1").find("unknown effect 'cogging' (known: backlash, compliance,"),
            std::string::npos)
      << why("cogging:amplitude_Nm=1");
  EXPECT_NE(why("stribeck:speed=1").find(
                "has no parameter 'speed' (its parameters: static_excess_Nm, stribeck_velocity_rad_s)"),
            std::string::npos)
      << why("stribeck:speed=1");
}

TEST(LibraryEffects, BadSpecsAreRejectedWithTheReason) {
  for (const char* bad : {"cogging:amplitude_Nm=1", "stribeck:speed=1", "stribeck:static_excess_Nm=abc",
                          "stribeck:static_excess_Nm", "gravity:amplitude_Nm=nan", "gravity:amplitude_Nm=",
                          "stribeck:excess=0.002"}) {
    EXPECT_THROW(model::parse_effect_specs(bad), std::invalid_argument) << bad;
  }
}

TEST(LibraryEffects, ASpecFromAModelFileIsCheckedAsTheTextIs) {
  const model::EffectSpec s =
      model::effect_from_params("stribeck", {{"static_excess_Nm", 0.002}, {"stribeck_velocity_rad_s", 0.1}});
  EXPECT_EQ(s.params,
            model::parse_effect_spec("stribeck:static_excess_Nm=0.002,stribeck_velocity_rad_s=0.1").params);
  const auto refused = [](const std::string& id, const model::NamedValues& params, const std::string& why) {
    try {
      model::effect_from_params(id, params);
      ADD_FAILURE() << id << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refused("stribeck", {{"excess", 0.002}}, "excess");  // simulate's old name
  refused("magnetism", {{"amplitude_Nm", 1.0}}, "unknown effect 'magnetism'");
  refused("time_delay", {{"delay_s", -0.001}}, "delay_s");
}

TEST(LibraryEffects, ModelTermsFoldIntoTheKnob) {
  KnobParams k = *presets::knob("moderate-detents");
  for (const auto& s : model::parse_effect_specs(
           "spring:stiffness_Nm_per_rad=0.01,cubic_Nm_per_rad3=0.5;detent_shape:a2_Nm=0.003,b3_Nm=-0.001")) {
    EXPECT_TRUE(apply_to_knob(s, k)) << s.id();
  }
  EXPECT_DOUBLE_EQ(k.spring.K, 0.01);
  EXPECT_DOUBLE_EQ(k.spring.K3, 0.5);
  EXPECT_DOUBLE_EQ(k.detents.a[2], 0.003);
  EXPECT_DOUBLE_EQ(k.detents.b[3], -0.001);
  EXPECT_GE(k.detents.harmonics, 4u);
  EXPECT_FALSE(apply_to_knob(model::parse_effect_spec("offset:offset_Nm=1"), k));
  EXPECT_THROW(make_knob_effect(model::parse_effect_spec("spring:stiffness_Nm_per_rad=1")), std::invalid_argument);
}

TEST(LibraryEffects, KnobEffectsAreTheModelTerms) {
  const KnobMotion m{0.7, -0.05, 3.0};
  const auto effect = [](const char* text) { return make_knob_effect(model::parse_effect_spec(text)); };
  const auto stribeck = effect("stribeck:static_excess_Nm=0.002,stribeck_velocity_rad_s=0.1");
  EXPECT_DOUBLE_EQ(stribeck->torque(m, 0.0), (model::Stribeck<double>{0.002, 0.1}.torque(-0.05)));
  const auto gravity = effect("gravity:amplitude_Nm=0.003,phase_rad=0.2");
  EXPECT_DOUBLE_EQ(gravity->torque(m, 0.0), 0.003 * std::sin(0.9));
  // A period of 0.1π rad: 20 per revolution, sin(θ/0.05 + φ).
  const auto periodic = effect("periodic_torque:amplitude_Nm=0.001,period_rad=0.3141592653589793,phase_rad=1");
  EXPECT_DOUBLE_EQ(periodic->torque(m, 0.0), 0.001 * std::sin(0.7 / 0.05 + 1));
  const auto bumpy = effect("position_friction:depth_Nm=0.002,period_rad=0.3141592653589793,phase_rad=1");
  EXPECT_DOUBLE_EQ(bumpy->torque(m, 0.0), -0.002 * std::sin(0.7 / 0.05 + 1));
  const auto drag = effect("nonlinear_damping:coefficient=0.01");  // exponent 2 by default
  EXPECT_DOUBLE_EQ(drag->torque(m, 0.0), -0.01 * 0.05 * 0.05);
  const auto drift = effect("drift:rate_Nm_per_s=1e-4,t0_s=2");
  EXPECT_DOUBLE_EQ(drift->torque(m, 5.0), -1e-4 * 3.0);
  const auto offset = effect("offset:offset_Nm=0.004");
  EXPECT_DOUBLE_EQ(offset->torque(m, 0.0), 0.004);
}

TEST(LibraryEffects, SensorReadsTheModelPlusTheEffect) {
  // As Knob.SensorReadsEq6TorqueOfTheTrueMotion, with a Stribeck effect: while
  // the knob slides the coupling torque is Eq. 6 plus the effect's torque.
  PlantConfig c;
  c.knob = *presets::knob("moderate-detents");
  Plant p(c);
  const auto spec = model::parse_effect_spec("stribeck:static_excess_Nm=0.003,stribeck_velocity_rad_s=0.3");
  p.add_effect(make_knob_effect(spec));
  const model::Stribeck<double> stribeck{0.003, 0.3};
  const auto model = thesis_model(c.knob);
  test::PositionLoop loop;
  const double dt = 2e-4;
  int sliding = 0, near_zero = 0;
  for (int k = 0; k < 15000; ++k) {
    const double t = k * dt, x = 1.5 * t / 3.0;
    const double phase = std::numbers::pi / 1.5 * x * x;
    p.step(loop.command(p, std::sin(phase), 2 * std::numbers::pi * x / 3.0 * std::cos(phase), dt), dt);
    const PlantState& s = p.state();
    if (std::abs(s.knob_velocity) <= 1.5 * c.knob.stick.dv) continue;
    ++sliding;
    near_zero += std::abs(s.knob_velocity) < 0.3 ? 1 : 0;
    const double tau = model.torque({s.knob_angle, s.knob_velocity, s.knob_accel}) +
                       stribeck.torque(s.knob_velocity);
    // 5e-5: the plant holds knob torques over a substep, and this term is
    // steep near zero speed (ΔC/v_s = 0.01 N·m per rad/s).
    ASSERT_NEAR(s.coupling_torque, tau, 5e-5) << t;
  }
  EXPECT_GT(sliding, 12000);
  EXPECT_GT(near_zero, 200);  // the effect was exercised
}

TEST(LibraryEffects, BacklashLeavesTheSensorEmptyWhileTheDriveCrossesThePlay) {
  // A knob with friction only, driven by a position loop through a slow
  // sinusoid: after each reversal the drive crosses the play while the
  // mechanism stands, so the sensor reads next to nothing for `width` of
  // travel, then the full friction again. No chatter at the faces: the
  // friction level holds within 10 % through every stroke.
  PlantConfig c = test::quiet({});
  c.knob.inertia.M = 1e-5;
  c.knob.friction = {0.003, 0.0, 0.003, 0.0};
  KnobParams& k = c.knob;
  ASSERT_TRUE(apply_to_knob(model::parse_effect_spec("backlash:width_rad=0.01"), k));
  EXPECT_DOUBLE_EQ(k.backlash, 0.01);
  Plant p(c);
  test::PositionLoop loop;
  const double dt = 1e-4, A = 0.1, w = 2 * std::numbers::pi * 0.5;  // ±0.1 rad at 0.5 Hz
  std::vector<double> quiet_travel;
  double quiet_from = std::nan("");
  int mid_stroke = 0;
  for (int n = 0; n < 50000; ++n) {
    const double t = n * dt;
    p.step(loop.command(p, A * std::sin(w * t), A * w * std::cos(w * t), dt), dt);
    const double tau = p.state().coupling_torque, at = p.state().motor_angle;
    if (std::abs(tau) < 0.3e-3) {
      if (std::isnan(quiet_from)) quiet_from = at;
    } else if (!std::isnan(quiet_from)) {
      if (t > 0.5) quiet_travel.push_back(std::abs(at - quiet_from));
      quiet_from = std::nan("");
    }
    if (t > 0.5 && std::abs(std::cos(w * t)) > 0.5) {  // mid-stroke: sliding
      ++mid_stroke;
      EXPECT_NEAR(std::abs(tau), 0.003, 3e-4) << t;
    }
  }
  ASSERT_GE(quiet_travel.size(), 4u);  // two reversals a cycle, 2.25 cycles after 0.5 s
  for (const double travel : quiet_travel) EXPECT_NEAR(travel, 0.01, 0.0015);
  EXPECT_GT(mid_stroke, 20000);
}

TEST(LibraryEffects, ADetentPullingThroughThePlayIsHeldBackByTheFarFace) {
  // Turned steadily across the moderate-detents knob's detents: where a
  // detent's downslope pulls the mechanism ahead (harder than its kinetic
  // friction holds), it snaps across the 3.2 mrad play and presses the far
  // face, and the knob holds it back. The sensor reads the detent's pull
  // there as it does without play (Eq. 6 at the mechanism's angle, half the
  // play ahead), not the nothing of a mechanism running free: it cannot
  // leave the knob behind by more than the play.
  const auto peak_assist = [](double width) {
    PlantConfig c = test::quiet({});
    c.knob = *presets::knob("moderate-detents");
    c.knob.backlash = width;
    Plant p(c);
    test::PositionLoop loop;
    const double dt = 1e-4, v = -2.0;  // rad/s, over 1.2 rad: two detent periods and more
    double ref = 0.0, peak = 0.0;
    for (int n = 0; n < 6000; ++n) {
      ref += v * dt;
      p.step(loop.command(p, ref, v, dt), dt);
      if (n > 2000) peak = std::max(peak, p.state().coupling_torque);  // restraining: > 0 moving −
      EXPECT_LE(std::abs(p.state().knob_angle - p.state().motor_angle), 0.01);
    }
    return peak;
  };
  const double without = peak_assist(0.0);
  EXPECT_GT(without, 0.008);  // 11 mN·m detents less 2 mN·m of friction
  EXPECT_NEAR(peak_assist(0.0032), without, 0.1 * without);
}

TEST(LibraryEffects, WithoutPlayTheSensorReadsFrictionRightAfterAReversal) {
  // The same drive without backlash: the torque changes sign within a few
  // hundredths of a milliradian of travel (the coupling's twist), so the
  // quiet stretch above is the play's doing.
  PlantConfig c = test::quiet({});
  c.knob.inertia.M = 1e-5;
  c.knob.friction = {0.003, 0.0, 0.003, 0.0};
  Plant p(c);
  test::PositionLoop loop;
  const double dt = 1e-4, A = 0.1, w = 2 * std::numbers::pi * 0.5;
  double quiet_from = std::nan(""), longest = 0.0;
  for (int n = 5000; n < 30000; ++n) {
    const double t = n * dt;
    p.step(loop.command(p, A * std::sin(w * t), A * w * std::cos(w * t), dt), dt);
    const double tau = p.state().coupling_torque, at = p.state().motor_angle;
    if (std::abs(tau) < 0.3e-3) {
      if (std::isnan(quiet_from)) quiet_from = at;
      longest = std::max(longest, std::abs(at - quiet_from));
    } else {
      quiet_from = std::nan("");
    }
  }
  EXPECT_LT(longest, 1e-3);
}
