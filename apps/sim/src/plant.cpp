#include "knoblab/sim/plant.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace knoblab::sim {

namespace {

constexpr std::uint64_t kTorqueStream = 0x746F727175650001ull;  // "torque"
constexpr std::uint64_t kAccelStream = 0x616363656C000002ull;   // "accel"

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("sim::Plant: ") + what);
}

void validate(const PlantConfig& c) {
  const auto& m = c.motor;
  require(m.K > 0 && m.J > 0 && m.b >= 0 && m.L > 0 && m.R > 0 && m.extra_inertia >= 0,
          "motor K, J, L, R must be > 0 and b, extra_inertia >= 0");
  const auto& a = c.amp;
  require(a.dac_range > 0 && a.torque_per_volt > 0 && a.bus_voltage > 0 &&
              a.current_bandwidth_hz > 0 && a.peak_current > 0 && a.continuous_current > 0 &&
              a.continuous_current <= a.peak_current && a.rms_time_constant > 0 &&
              a.release_fraction > 0 && a.release_fraction <= 1,
          "amplifier parameters out of range");
  require(c.coupling.stiffness > 0 && c.coupling.damping >= 0 && c.coupling.gripper_inertia >= 0,
          "coupling needs stiffness > 0, damping >= 0, gripper_inertia >= 0");
  if (c.load == Load::Knob) {
    const std::string_view why = check(c.knob);
    require(why.empty(), why.data());
    require(c.knob.inertia.M + c.coupling.gripper_inertia > 0,
            "knob-side inertia (M + gripper) must be > 0");
  }
  require(c.encoder.cpr > 0, "encoder cpr must be > 0");
  require(c.torque_sensor.saturation > 0 && c.torque_sensor.noise_sigma >= 0 &&
              c.torque_sensor.scale.volts_per_Nm > 0,
          "torque sensor parameters out of range");
  require(c.accel.C_cal > 0 && c.accel.radius > 0 && c.accel.full_scale_g > 0 &&
              c.accel.noise_pp_fraction >= 0,
          "accelerometer parameters out of range");
  require(c.torque_sensor.adc.bits > 1 && c.torque_sensor.adc.bits < 32 &&
              c.accel.adc.bits > 1 && c.accel.adc.bits < 32 && c.torque_sensor.adc.range > 0 &&
              c.accel.adc.range > 0,
          "ADC needs 2..31 bits and range > 0");
  require(c.min_substeps >= 1 && c.max_substep > 0, "substeps out of range");
  // The delay line holds delay / max_substep samples: bound both.
  require(c.torque_sensor.delay >= 0 && c.torque_sensor.delay <= 0.1 &&
              c.torque_sensor.delay <= 1e6 * c.max_substep,
          "torque sensor delay must be 0 … 0.1 s and at most 1e6 substeps");
}

}  // namespace

Plant::Plant(const PlantConfig& cfg)
    : cfg_((validate(cfg), cfg)),
      amp_(cfg_.amp, cfg_.motor),
      accel_(cfg_.accel, cfg_.mounting),
      bearing_{0.0, cfg_.motor.b, 0.0, cfg_.motor.b},
      knob_inertia_(cfg_.knob.inertia.M + cfg_.coupling.gripper_inertia),
      torque_delay_(cfg_.torque_sensor.delay, cfg_.max_substep) {
  const auto& k = cfg_.knob;
  dry_friction_ = k.friction.C_neg > 0 || k.friction.C_pos > 0 || k.stick.dv > 0;
  reset();
}

void Plant::add_effect(std::unique_ptr<KnobEffect> effect) {
  if (effect) effects_.push_back(std::move(effect));
}

void Plant::reset() {
  state_ = PlantState{};
  state_.motor_angle = state_.knob_angle = cfg_.initial_angle;
  amp_.reset();
  torque_rng_.seed(splitmix64(cfg_.seed ^ kTorqueStream));
  accel_rng_.seed(splitmix64(cfg_.seed ^ kAccelStream));
  for (auto& e : effects_) e->reset();
  play_.width = cfg_.knob.backlash;
  play_.reset(cfg_.initial_angle);
  mech_velocity_ = 0.0;
  dahl_.presliding = cfg_.knob.presliding;
  dahl_.reset();
  torque_delay_.reset(state_.t, state_.coupling_torque);
  accel_.reset(cfg_.initial_angle);
  sample();
}

const SensorReadings& Plant::step(double command_volts, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) return readings_;
  if (!std::isfinite(command_volts)) command_volts = 0.0;
  const double want = std::ceil(dt / cfg_.max_substep * (1.0 - 1e-12));
  const int n = std::max(cfg_.min_substeps, static_cast<int>(std::min(want, 1e9)));
  const double h = dt / n;
  const double t0 = state_.t;
  for (int s = 0; s < n; ++s) substep(command_volts, h);
  state_.t = t0 + dt;  // no drift from summing h
  sample();
  return readings_;
}

void Plant::substep(double command, double h) {
  auto& s = state_;
  s.current = amp_.step(command, s.motor_velocity, h);
  s.voltage = amp_.voltage();
  const double motor_force = cfg_.motor.torque(s.current) - bearing_.torque(s.motor_velocity);
  switch (cfg_.load) {
    case Load::Free: step_free(motor_force, h); break;
    case Load::Anchored: step_held(motor_force, h); break;
    case Load::Knob: step_knob(motor_force, h); break;
  }
  const bool on_knob = cfg_.accel.side == AccelerometerParams::Side::Knob;
  accel_.track(on_knob ? s.knob_accel : s.motor_accel, on_knob ? s.knob_angle : s.motor_angle, h);
  s.t += h;
  if (torque_delay_.active()) torque_delay_.push(s.t, s.coupling_torque);
}

// The rotor against a knob side that does not move this substep, with the
// coupling implicit in the new rotor speed w:
//   J(w − ω)/h = F − k·e − g·w,  g = k·h + c  (τ_c = k·(e + h·w) + c·w)
Plant::MotorStep Plant::motor_against_held_knob(double motor_force, double h) const {
  const auto& s = state_;
  const double jm = cfg_.motor.inertia();
  const double k = cfg_.coupling.stiffness;
  const double g = k * h + cfg_.coupling.damping;
  const double e = s.motor_angle - s.knob_angle;
  const double w = (s.motor_velocity + h / jm * (motor_force - k * e)) / (1.0 + h * g / jm);
  return {w, k * e + g * w};
}

void Plant::step_free(double motor_force, double h) {
  auto& s = state_;
  const double w = s.motor_velocity + h * motor_force / cfg_.motor.inertia();
  s.motor_accel = (w - s.motor_velocity) / h;
  s.motor_velocity = w;
  s.motor_angle += h * w;
  // No knob: its side is the shaft itself, and nothing loads the sensor.
  s.knob_angle = s.motor_angle;
  s.knob_velocity = s.motor_velocity;
  s.knob_accel = s.motor_accel;
  s.coupling_torque = 0.0;
}

void Plant::step_held(double motor_force, double h) {
  auto& s = state_;
  const MotorStep m = motor_against_held_knob(motor_force, h);
  s.motor_accel = (m.omega - s.motor_velocity) / h;
  s.motor_velocity = m.omega;
  s.motor_angle += h * m.omega;
  s.knob_velocity = s.knob_accel = 0.0;
  s.coupling_torque = m.torque;
}

double Plant::effects_torque(const KnobMotion& k) const {
  double tau = 0.0;
  for (const auto& e : effects_) tau += e->torque(k, state_.t);
  return tau;
}

// Which face of the play the knob is against: +1 the knob's leading side
// (it pushes the mechanism forward or is held back by it), −1 the trailing
// side, 0 inside the play. Without play: always +1.
int Plant::play_face() const {
  if (cfg_.knob.backlash <= 0.0) return 1;
  const double e = state_.knob_angle - play_.knob, half = 0.5 * cfg_.knob.backlash;
  const double tol = 1e-9 * half;
  return e >= half - tol ? 1 : e <= -half + tol ? -1 : 0;
}

// The detent mechanism on its own (massless, the knob not touching it): it
// stays put while its friction holds its detent and effect torques (static
// limits when it stood last substep), else it slides at the speed where
// kinetic friction balances them — a detent's downslope pulls it ahead of
// the knob. Without viscous friction it jumps (a large speed).
double Plant::mechanism_free_velocity(double tau_pos) const {
  const KnobParams& kp = cfg_.knob;
  const double pull = -tau_pos;  // drives the mechanism forward
  const bool fwd = pull > 0.0;
  const bool moving = !kp.stick.sticking(mech_velocity_) && mech_velocity_ != 0.0;
  const double hold = moving ? (fwd ? kp.friction.C_pos : kp.friction.C_neg)
                             : (fwd ? kp.stick.D_pos : kp.stick.D_neg);
  const double excess = std::abs(pull) - hold;
  if (!(excess > 0.0)) return 0.0;
  const double b = fwd ? kp.friction.B_pos : kp.friction.B_neg;
  const double v = b > 0.0 ? excess / b : 1e3;
  return fwd ? v : -v;
}

// The knob side, after the coupling (gripper and knob cap, inertia M), drives
// the detent mechanism through the play (KnobParams::backlash): the pin of
// a slot. The massless mechanism's friction, detents and effects load the
// knob only while a face is pressed — the knob moving into it faster than
// the mechanism would move on its own — and never pull the faces apart.
// Inside the play the knob turns against its inertia alone. Driven by the
// knob alone this is model::Backlash, the operator discovery fits.
void Plant::step_knob(double motor_force, double h) {
  auto& s = state_;
  const KnobParams& kp = cfg_.knob;
  const double w = s.knob_velocity;
  const bool play = kp.backlash > 0.0;
  const int face = play_face();
  const double phi = play ? play_.knob : s.knob_angle;  // the mechanism
  const double tau_pos = position_torque(kp, phi, w) + effects_torque({phi, w, s.knob_accel});
  const double v_free = play ? mechanism_free_velocity(tau_pos) : 0.0;
  // A pressed face pushes (+1: back on the knob, −1: the knob forward), never pulls.
  const auto pushes = [&](double mech_torque) { return !play || face * mech_torque >= 0.0; };

  double mech = 0.0;  // the mechanism's torque on the knob (needed to move it)
  bool engaged = !play || (face > 0 && w >= v_free) || (face < 0 && w <= v_free);
  if (engaged) {
    double friction = 0.0;
    if (kp.stick.sticking(w)) {
      // Karnopp (Eq. 7): try the knob held still; if the friction needed stays
      // within the static limits (and the face is pressed), it is stuck.
      const MotorStep m = motor_against_held_knob(motor_force, h);
      const double tau_other = m.torque - tau_pos;
      friction = kp.stick.torque(w, tau_other, kp.friction);
      if (friction == tau_other && pushes(m.torque)) {
        s.motor_accel = (m.omega - s.motor_velocity) / h;
        s.motor_velocity = m.omega;
        s.motor_angle += h * m.omega;
        s.knob_accel = -w / h;
        s.knob_velocity = 0.0;
        s.coupling_torque = m.torque;
        s.stuck = true;
        mech_velocity_ = 0.0;
        for (auto& e : effects_) e->advance({phi, 0.0, s.knob_accel}, s.t, h);
        return;
      }
    } else {
      friction = sliding_friction(w);
    }
    mech = tau_pos + friction;
    engaged = pushes(mech);
    if (!engaged) mech = 0.0;
  }
  s.stuck = false;

  // Both sides move: solve the coupling implicitly in the new relative speed
  // d = ω_m' − ω_k', with the knob's own torques frozen over the substep.
  const double jm = cfg_.motor.inertia();
  const double jk = knob_inertia_;
  const double k = cfg_.coupling.stiffness;
  const double g = k * h + cfg_.coupling.damping;
  const double e = s.motor_angle - s.knob_angle;
  const double knob_force = -mech;
  const double inv = 1.0 / jm + 1.0 / jk;
  const double d = (s.motor_velocity - w + h * (motor_force / jm - knob_force / jk) - h * inv * k * e) /
                   (1.0 + h * g * inv);
  const double tau_c = k * e + g * d;
  const double wm = s.motor_velocity + h * (motor_force - tau_c) / jm;
  double wk = w + h * (knob_force + tau_c) / jk;
  // Dry friction can stop the knob but not reverse it within one substep:
  // stop at zero so the next substep runs the stick test (or restarts from 0).
  if (engaged && dry_friction_ && w != 0.0 && wk * w < 0.0) wk = 0.0;

  s.motor_accel = (wm - s.motor_velocity) / h;
  s.motor_velocity = wm;
  s.motor_angle += h * wm;
  s.knob_accel = (wk - w) / h;
  s.knob_velocity = wk;
  s.knob_angle += h * wk;
  s.coupling_torque = tau_c;
  // The mechanism: with the knob while engaged (pushed by one face or held
  // back by the other), else on its own; the faces of the play bound it
  // either way.
  if (play) {
    play_.knob += h * (engaged ? wk : v_free);
    play_.update(s.knob_angle);
    mech_velocity_ = (play_.knob - phi) / h;
  } else {
    mech_velocity_ = wk;
  }
  const double a_mech = play ? 0.0 : s.knob_accel;  // massless: no inertia of its own to report
  for (auto& eff : effects_) eff->advance({play ? play_.knob : s.knob_angle, mech_velocity_, a_mech}, s.t, h);
  // Dahl follows the mechanism's travel (none while stuck: z stands with it).
  if (kp.presliding > 0.0) dahl_.update(h * mech_velocity_);
}

// Eq. 6's sliding law, or under presliding hysteresis its Dahl form
// (CoulombViscous::torque_dahl, the one discovery fits). Dahl is passive (storage C·θ_p·z²/2 grows by at
// most τ·dθ), so friction stays dissipative over any path.
double Plant::sliding_friction(double w) const {
  const model::CoulombViscous<double>& f = cfg_.knob.friction;
  return cfg_.knob.presliding > 0.0 ? f.torque_dahl(w, dahl_.z) : f.torque(w);
}

void Plant::sample() {
  const auto& s = state_;
  readings_.t = s.t;
  readings_.encoder_counts = cfg_.encoder.to_counts(s.motor_angle);
  const double tau = torque_delay_.active() ? torque_delay_.read(s.t) : s.coupling_torque;
  readings_.torque_volts = cfg_.torque_sensor.sample(tau, torque_rng_);
  readings_.torque = cfg_.torque_sensor.scale.to_torque(readings_.torque_volts);
  readings_.accel_volts = accel_.sample(accel_rng_);
}

}  // namespace knoblab::sim
