#include "knoblab/sim/library_effects.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "knoblab/model/effects.hpp"

namespace knoblab::sim {

namespace {

using model::Acts;
using model::Effect;
using model::EffectSpec;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// A library term as a knob effect: the term by value, evaluated in place.
template <typename F>
class TermEffect final : public KnobEffect {
 public:
  explicit TermEffect(F f) : f_(std::move(f)) {}
  double torque(const KnobMotion& knob, double t) const override { return f_(knob, t); }

 private:
  F f_;
};

template <typename F>
std::unique_ptr<KnobEffect> effect(F f) {
  return std::make_unique<TermEffect<F>>(std::move(f));
}

// model::Detents' P, θ per radian of phase, from a period over position.
double phase_scale(const EffectSpec& s) { return s.value("period_rad") / kTwoPi; }

}  // namespace

bool apply_to_knob(const EffectSpec& s, KnobParams& knob) {
  if (s.row().acts != Acts::KnobStructure) return false;
  switch (s.effect) {
    case Effect::Spring:
      knob.spring.K = s.value("stiffness_Nm_per_rad");
      knob.spring.K3 = s.value("cubic_Nm_per_rad3");
      knob.spring.theta0 = s.value("centre_rad");
      return true;
    case Effect::Backlash: knob.backlash = s.value("width_rad"); return true;
    case Effect::Hysteresis: knob.presliding = s.value("presliding_angle_rad"); return true;
    case Effect::Endstop:
      knob.walls.lo = -s.value("position_rad");
      knob.walls.hi = s.value("position_rad");
      knob.walls.K = s.value("stiffness_Nm_per_rad");
      knob.walls.B = s.value("damping_Nm_s_per_rad");
      knob.walls.limit = s.value("max_torque_Nm");  // ∞ when not given: a mechanical stop
      return true;
    case Effect::DetentShape:
      for (std::size_t k = 2; k <= 4; ++k) {
        knob.detents.a[k] = s.value("a" + std::to_string(k) + "_Nm");
        knob.detents.b[k] = s.value("b" + std::to_string(k) + "_Nm");
      }
      knob.detents.harmonics = std::max<std::size_t>(knob.detents.harmonics, 4);
      return true;
    default: throw std::logic_error("effect '" + std::string(s.id()) + "' acts on the knob but is not folded in");
  }
}

bool apply_to_plant(const EffectSpec& s, PlantConfig& plant) {
  switch (s.effect) {
    case Effect::TimeDelay: plant.torque_sensor.delay = s.value("delay_s"); return true;
    case Effect::Saturation: plant.torque_sensor.saturation = s.value("limit_Nm"); return true;
    case Effect::Compliance: break;
    default: return false;
  }
  CouplingParams& c = plant.coupling;
  const double J = plant.knob.inertia.M + c.gripper_inertia;
  const bool tuned = s.has("frequency_hz") || s.has("zeta");
  if (tuned && !(J > 0.0))
    throw std::invalid_argument(
        "effect 'compliance': frequency_hz and zeta need a knob side with inertia (M + gripper > 0)");
  const double k = s.has("frequency_hz") ? CouplingParams::tuned(s.value("frequency_hz"), 1.0, J).stiffness
                                          : s.value("stiffness_Nm_per_rad");
  if (s.has("damping_Nm_s_per_rad")) {
    c.damping = s.value("damping_Nm_s_per_rad");
  } else if (s.has("zeta")) {
    c.damping = 2.0 * s.value("zeta") * std::sqrt(k * J);
  } else {
    c.damping *= std::sqrt(k / c.stiffness);  // the same damping ratio
  }
  c.stiffness = k;
  return true;
}

std::unique_ptr<KnobEffect> make_knob_effect(const EffectSpec& s) {
  switch (s.effect) {
    case Effect::Offset: {
      const model::Offset<double> o{s.value("offset_Nm")};
      return effect([o](const KnobMotion&, double) { return o.torque(); });
    }
    case Effect::Gravity: {
      const model::OncePerRev<double> g{s.value("amplitude_Nm"), s.value("phase_rad")};
      return effect([g](const KnobMotion& k, double) { return g.torque(k.theta); });
    }
    case Effect::Stribeck: {
      const model::Stribeck<double> f{s.value("static_excess_Nm"), s.value("stribeck_velocity_rad_s")};
      return effect([f](const KnobMotion& k, double) { return f.torque(k.omega); });
    }
    case Effect::NonlinearDamping: {
      const model::PowerDamping<double> f{s.value("coefficient"), s.value("exponent")};
      return effect([f](const KnobMotion& k, double) { return f.torque(k.omega); });
    }
    case Effect::PositionFriction: {
      const model::PositionFriction<double> f{s.value("depth_Nm"), phase_scale(s), s.value("phase_rad")};
      return effect([f](const KnobMotion& k, double) { return f.torque(k.theta, k.omega); });
    }
    case Effect::PeriodicTorque: {
      model::Detents<double> w;
      w.A = s.value("amplitude_Nm");
      w.P = phase_scale(s);
      w.S = s.value("phase_rad");
      return effect([w](const KnobMotion& k, double) { return w.torque(k.theta); });
    }
    case Effect::Drift: {
      const model::FrictionDrift<double> f{s.value("rate_Nm_per_s"), s.value("t0_s")};
      return effect([f](const KnobMotion& k, double t) { return f.torque(k.omega, t); });
    }
    default:
      throw std::invalid_argument("effect '" + std::string(s.id()) + "' is not a knob torque (it acts on the " +
                                  std::string(model::acts_name(s.row().acts)) + ")");
  }
}

}  // namespace knoblab::sim
