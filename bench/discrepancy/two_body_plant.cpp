#include "two_body_plant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "knoblab/interchange/number_text.hpp"
#include "knoblab/model/filters.hpp"

namespace knoblab::bench {

namespace {

constexpr double kPi = std::numbers::pi;
// The knob settles against the held motor this long before the first sample.
constexpr double kRestSeconds = 0.25;
// Substep bound for the stiff parts: h·√(k/J) and h·c/J at most this.
constexpr double kStepLimit = 0.2;

double sgn(double x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0; }

std::string num(double x) { return interchange::shortest(x); }

// Everything on the knob but friction and inertia: detents, the second
// periodic torque, spring, gravity, endstops.
double position_torque(const TwoBodyKnob& k, double theta, double omega) {
  const double phi = theta / k.detent_period + k.detent_phase;
  double tau = k.detent_amplitude * std::sin(phi);
  for (int n = 2; n <= 4; ++n) {
    const double a = k.detent_sin[static_cast<std::size_t>(n - 2)];
    const double b = k.detent_cos[static_cast<std::size_t>(n - 2)];
    if (a != 0.0 || b != 0.0) tau += a * std::sin(n * phi) + b * std::cos(n * phi);
  }
  if (k.periodic_amplitude != 0.0)
    tau += k.periodic_amplitude * std::sin(2.0 * kPi * theta / k.periodic_period_rad + k.periodic_phase);
  tau += k.spring * theta + k.spring_cubic * theta * theta * theta;
  if (k.gravity != 0.0) tau += k.gravity * std::sin(theta + k.gravity_phase);
  if (k.endstop_angle > 0.0) {
    // A stop pushes the knob back out; its damping never pulls it in.
    if (theta > k.endstop_angle)
      tau += std::max(0.0, k.endstop_stiffness * (theta - k.endstop_angle) + k.endstop_damping * omega);
    else if (theta < -k.endstop_angle)
      tau += std::min(0.0, k.endstop_stiffness * (theta + k.endstop_angle) + k.endstop_damping * omega);
  }
  return tau;
}

double kinetic(const TwoBodyKnob& k, double direction) { return direction >= 0.0 ? k.coulomb_pos : k.coulomb_neg; }
double breakaway(const TwoBodyKnob& k, double direction) { return kinetic(k, direction) + k.static_excess; }

// F(ω) while sliding: Stribeck's curve, viscous and quadratic drag.
double sliding_friction(const TwoBodyKnob& k, double w) {
  if (w == 0.0) return 0.0;
  const double s = sgn(w);
  const double v = w / k.stribeck_speed;
  return s * (kinetic(k, s) + k.static_excess * std::exp(-v * v)) + (w > 0.0 ? k.viscous_pos : k.viscous_neg) * w +
         k.drag * w * std::abs(w);
}

struct CouplingTorque {
  double torque = 0.0;
  bool in_play = false;
};

CouplingTorque coupling_torque(const Coupling& c, double twist, double twist_rate) {
  if (c.play <= 0.0) return {c.stiffness * twist + c.damping * twist_rate, false};
  const double half = 0.5 * c.play;
  if (twist > half) return {std::max(0.0, c.stiffness * (twist - half) + c.damping * twist_rate), false};
  if (twist < -half) return {std::min(0.0, c.stiffness * (twist + half) + c.damping * twist_rate), false};
  return {0.0, true};
}

struct KnobState {
  double theta = 0.0, omega = 0.0;
  bool stuck = true;
};

// Every torque on the knob but friction's: the coupling's, less the
// position torques.
double drive_on(const TwoBodyConfig& cfg, const MotorState& m, const KnobState& s) {
  return coupling_torque(cfg.coupling, m.theta - s.theta, m.omega - s.omega).torque -
         position_torque(cfg.knob, s.theta, s.omega);
}

// The knob's acceleration under `drive`: none while static friction holds a
// standing knob; one breaking away starts from the breakaway level.
double acceleration(const TwoBodyKnob& k, double drive, const KnobState& s) {
  if (s.stuck) {
    const double dir = sgn(drive);
    return std::abs(drive) <= breakaway(k, dir) ? 0.0 : (drive - dir * breakaway(k, dir)) / k.inertia;
  }
  return (drive - sliding_friction(k, s.omega)) / k.inertia;
}

// One semi-implicit Euler substep of the knob against the motor at m.
void substep(const TwoBodyConfig& cfg, const MotorState& m, double h, KnobState& s) {
  const double drive = drive_on(cfg, m, s);
  const double a = acceleration(cfg.knob, drive, s);
  if (s.stuck) {
    if (a == 0.0) return;  // static friction balances it
    s.stuck = false;
    s.omega = a * h;
    s.theta += s.omega * h;
    return;
  }
  const double w = s.omega + a * h;
  if (w * s.omega <= 0.0 && std::abs(drive) <= breakaway(cfg.knob, sgn(drive))) {
    // The speed would cross zero here, and static friction can hold it.
    s.omega = 0.0;
    s.stuck = true;
    return;
  }
  s.omega = w;
  s.theta += w * h;
}

int substeps_per_sample(const TwoBodyConfig& cfg) {
  const double dt = 1.0 / cfg.camera.rate_hz;
  double h = 1.0 / cfg.substep_hz;
  const double J = cfg.knob.inertia;
  if (!cfg.coupling.rigid()) {
    h = std::min(h, kStepLimit / std::sqrt(cfg.coupling.stiffness / J));
    if (cfg.coupling.damping > 0.0) h = std::min(h, kStepLimit * J / cfg.coupling.damping);
  }
  if (cfg.knob.endstop_angle > 0.0) {
    if (cfg.knob.endstop_stiffness > 0.0) h = std::min(h, kStepLimit / std::sqrt(cfg.knob.endstop_stiffness / J));
    if (cfg.knob.endstop_damping > 0.0) h = std::min(h, kStepLimit * J / cfg.knob.endstop_damping);
  }
  return std::max(1, static_cast<int>(std::ceil(dt / h - 1e-9)));
}

void require(bool ok, const std::string& field, const std::string& what, double got) {
  if (!ok) throw std::invalid_argument(field + " must be " + what + ", got " + num(got));
}

void require_finite_nonnegative(double x, const std::string& field) { require(std::isfinite(x) && x >= 0.0, field, "finite and ≥ 0", x); }

std::string stimulus_json(const MotorStimulus& s) {
  if (s.kind == MotorStimulus::Kind::SweptSine)
    return "{\"kind\": \"swept_sine\", \"equation\": 8, \"a\": " + num(s.sine.a) + ", \"b\": " + num(s.sine.b) +
           ", \"c\": " + num(s.sine.c) + ", \"d\": " + num(s.sine.d) + "}";
  const TriangleSweep& t = s.triangle;
  return "{\"kind\": \"triangle\", \"amplitude_rad\": " + num(t.amplitude_rad) + ", \"slowest_rad_s\": " +
         num(t.slowest_rad_s) + ", \"fastest_rad_s\": " + num(t.fastest_rad_s) + ", \"rungs\": " +
         std::to_string(t.rungs) + ", \"turn_accel_rad_s2\": " + num(t.turn_accel_rad_s2) + "}";
}

// One leg from rest to rest over `distance` at cruise `speed` and `accel`:
// the time it takes, and where it is τ into it.
double leg_duration(double distance, double speed, double accel) {
  const double v = std::min(speed, std::sqrt(accel * distance));
  return 2.0 * v / accel + (distance - v * v / accel) / v;
}

MotorState along_leg(double distance, double speed, double accel, double tau) {
  const double v = std::min(speed, std::sqrt(accel * distance));
  const double ta = v / accel, da = 0.5 * v * ta;
  const double total = leg_duration(distance, speed, accel);
  if (tau <= 0.0) return {0.0, 0.0, 0.0};
  if (tau < ta) return {0.5 * accel * tau * tau, accel * tau, accel};
  if (tau < total - ta) return {da + v * (tau - ta), v, 0.0};
  if (tau < total) {
    const double left = total - tau;
    return {distance - 0.5 * accel * left * left, accel * left, -accel};
  }
  return {distance, 0.0, 0.0};
}

}  // namespace

double Coupling::damping_for(double zeta, double stiffness, double inertia) {
  return 2.0 * zeta * std::sqrt(stiffness * inertia);
}

MotorPath::MotorPath(const MotorStimulus& stimulus, double seconds) : stimulus_(stimulus) {
  if (stimulus.kind != MotorStimulus::Kind::Triangle) return;
  const TriangleSweep& tr = stimulus.triangle;
  // The ladder up and back down: rung indices 0, 1, …, R−1, R−2, …, 1.
  std::vector<double> speeds;
  for (int j = 0; j < tr.rungs; ++j)
    speeds.push_back(tr.rungs == 1 ? tr.slowest_rad_s
                                   : tr.slowest_rad_s * std::pow(tr.fastest_rad_s / tr.slowest_rad_s,
                                                                 static_cast<double>(j) / (tr.rungs - 1)));
  for (int j = tr.rungs - 2; j >= 1; --j) speeds.push_back(speeds[static_cast<std::size_t>(j)]);
  double t = 0.0, at = 0.0, to = tr.amplitude_rad;
  for (std::size_t i = 0; t <= seconds; ++i) {
    const double v = speeds[i % speeds.size()];
    legs_.push_back({t, at, to, v, tr.turn_accel_rad_s2});
    t += leg_duration(std::abs(to - at), v, tr.turn_accel_rad_s2);
    at = to;
    to = -to;
  }
}

MotorState MotorPath::at(double t) const {
  if (stimulus_.kind == MotorStimulus::Kind::SweptSine) {
    const auto k = stimulus_.sine.at(t);
    return {k.theta, k.omega, k.alpha};
  }
  if (t <= 0.0) return {0.0, 0.0, 0.0};
  const auto next = std::upper_bound(legs_.begin(), legs_.end(), t, [](double x, const Leg& l) { return x < l.start_s; });
  const Leg& leg = *(next - 1);
  const double dir = leg.to_rad > leg.from_rad ? 1.0 : -1.0;
  const MotorState s = along_leg(std::abs(leg.to_rad - leg.from_rad), leg.speed, leg.accel, t - leg.start_s);
  return {leg.from_rad + dir * s.theta, dir * s.omega, dir * s.alpha};
}

void validate(const TwoBodyConfig& c) {
  const TwoBodyKnob& k = c.knob;
  require(std::isfinite(k.inertia) && k.inertia > 0.0, "knob.inertia", "finite and > 0 kg·m²", k.inertia);
  require_finite_nonnegative(k.coulomb_pos, "knob.coulomb_pos");
  require_finite_nonnegative(k.coulomb_neg, "knob.coulomb_neg");
  require_finite_nonnegative(k.viscous_pos, "knob.viscous_pos");
  require_finite_nonnegative(k.viscous_neg, "knob.viscous_neg");
  require_finite_nonnegative(k.static_excess, "knob.static_excess");
  require(std::isfinite(k.stribeck_speed) && k.stribeck_speed > 0.0, "knob.stribeck_speed", "finite and > 0 rad/s",
          k.stribeck_speed);
  require_finite_nonnegative(k.drag, "knob.drag");
  require(std::isfinite(k.detent_period) && k.detent_period > 0.0, "knob.detent_period", "finite and > 0",
          k.detent_period);
  require(std::isfinite(k.periodic_period_rad) && k.periodic_period_rad > 0.0, "knob.periodic_period_rad",
          "finite and > 0 rad", k.periodic_period_rad);
  for (const double x : {k.detent_amplitude, k.detent_phase, k.periodic_amplitude, k.periodic_phase, k.spring,
                         k.spring_cubic, k.gravity, k.gravity_phase})
    require(std::isfinite(x), "every knob torque parameter", "finite", x);
  require_finite_nonnegative(k.endstop_angle, "knob.endstop_angle");
  require_finite_nonnegative(k.endstop_stiffness, "knob.endstop_stiffness");
  require_finite_nonnegative(k.endstop_damping, "knob.endstop_damping");
  const Coupling& g = c.coupling;
  require(g.stiffness > 0.0 && !std::isnan(g.stiffness), "coupling.stiffness", "> 0 N·m/rad (+inf: rigid)",
          g.stiffness);
  require_finite_nonnegative(g.damping, "coupling.damping");
  require_finite_nonnegative(g.play, "coupling.play");
  if (g.rigid() && g.play > 0.0)
    throw std::invalid_argument("coupling.play needs a finite coupling.stiffness: a rigid coupling has no play");
  require(std::isfinite(c.camera.rate_hz) && c.camera.rate_hz >= 1.0 && c.camera.rate_hz <= 1e5, "camera.rate_hz",
          "in [1, 100000] Hz", c.camera.rate_hz);
  require_finite_nonnegative(c.camera.torque_noise_rms, "camera.torque_noise_rms");
  require_finite_nonnegative(c.camera.accelerometer_noise_rms, "camera.accelerometer_noise_rms");
  require(c.camera.encoder_counts_per_rev >= 0, "camera.encoder_counts_per_rev", "≥ 0 (0: exact)",
          static_cast<double>(c.camera.encoder_counts_per_rev));
  require(std::isfinite(c.seconds) && c.seconds > 0.0 && c.seconds <= 3600.0, "seconds", "in (0, 3600]", c.seconds);
  require(std::isfinite(c.substep_hz) && c.substep_hz >= c.camera.rate_hz, "substep_hz",
          "finite and at least camera.rate_hz", c.substep_hz);
  if (c.stimulus.kind == MotorStimulus::Kind::SweptSine) {
    require(std::isfinite(c.stimulus.sine.d) && c.stimulus.sine.d > 0.0, "stimulus.sine.d", "finite and > 0 s",
            c.stimulus.sine.d);
  } else {
    const TriangleSweep& t = c.stimulus.triangle;
    require(std::isfinite(t.amplitude_rad) && t.amplitude_rad > 0.0, "stimulus.triangle.amplitude_rad",
            "finite and > 0", t.amplitude_rad);
    require(std::isfinite(t.slowest_rad_s) && t.slowest_rad_s > 0.0, "stimulus.triangle.slowest_rad_s",
            "finite and > 0", t.slowest_rad_s);
    require(std::isfinite(t.fastest_rad_s) && t.fastest_rad_s >= t.slowest_rad_s, "stimulus.triangle.fastest_rad_s",
            "finite and at least slowest_rad_s", t.fastest_rad_s);
    require(t.rungs >= 1, "stimulus.triangle.rungs", "≥ 1", t.rungs);
    require(std::isfinite(t.turn_accel_rad_s2) && t.turn_accel_rad_s2 > 0.0, "stimulus.triangle.turn_accel_rad_s2",
            "finite and > 0", t.turn_accel_rad_s2);
  }
}

TwoBodyRun run_two_body(const TwoBodyConfig& cfg) {
  validate(cfg);
  const MotorPath path(cfg.stimulus, cfg.seconds);
  const TwoBodyKnob& k = cfg.knob;
  const double dt = 1.0 / cfg.camera.rate_hz;
  const auto samples = static_cast<std::size_t>(std::llround(cfg.seconds * cfg.camera.rate_hz));
  TwoBodyRun run;
  run.substeps = cfg.coupling.rigid() ? 1 : substeps_per_sample(cfg);
  const double h = dt / run.substeps;

  std::mt19937_64 rng(cfg.camera.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double count = cfg.camera.encoder_counts_per_rev > 0
                           ? 2.0 * kPi / static_cast<double>(cfg.camera.encoder_counts_per_rev)
                           : 0.0;

  interchange::Capture& cap = run.capture;
  TwoBodyTruth& truth = run.truth;
  for (auto* v : {&cap.t, &cap.theta, &cap.alpha, &cap.torque, &truth.motor_theta, &truth.knob_theta, &truth.knob_omega,
                  &truth.coupling_torque})
    v->reserve(samples);

  KnobState s;
  const MotorState start = path.at(0.0);
  s.theta = start.theta;
  if (!cfg.coupling.rigid()) {
    const MotorState held{start.theta, 0.0, 0.0};
    const auto rest = static_cast<long>(std::llround(kRestSeconds / h));
    for (long j = 0; j < rest; ++j) substep(cfg, held, h, s);
  }

  for (std::size_t i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) * dt;
    const MotorState m = path.at(t);
    double tau = 0.0, alpha = m.alpha;
    bool in_play = false;
    if (cfg.coupling.rigid()) {
      // The knob is the motor: the sensor carries all the knob's torques.
      s = {m.theta, m.omega, m.omega == 0.0};
      tau = k.inertia * m.alpha + sliding_friction(k, m.omega) + position_torque(k, m.theta, m.omega);
    } else {
      const CouplingTorque c = coupling_torque(cfg.coupling, m.theta - s.theta, m.omega - s.omega);
      tau = c.torque;
      in_play = c.in_play;
      alpha = acceleration(k, drive_on(cfg, m, s), s);
    }
    cap.t.push_back(t);
    cap.theta.push_back(count > 0.0 ? std::floor(m.theta / count) * count : m.theta);
    cap.torque.push_back(tau + cfg.camera.torque_noise_rms * noise(rng));
    if (cfg.camera.accelerometer) cap.alpha.push_back(alpha + cfg.camera.accelerometer_noise_rms * noise(rng));
    truth.motor_theta.push_back(m.theta);
    truth.knob_theta.push_back(s.theta);
    truth.knob_omega.push_back(s.omega);
    truth.coupling_torque.push_back(tau);
    truth.stuck.push_back(s.stuck ? 1 : 0);
    truth.in_play.push_back(in_play ? 1 : 0);
    if (!cfg.coupling.rigid())
      for (int j = 0; j < run.substeps; ++j) substep(cfg, path.at(t + j * h), h, s);
  }

  // ω, and α without an accelerometer, as the CSV reader derives them for a
  // file without those columns.
  cap.omega = model::derivative(cap.t, cap.theta);
  cap.omega_derived = true;
  if (!cfg.camera.accelerometer) {
    cap.alpha = model::derivative(cap.t, cap.omega);
    cap.alpha_derived = true;
  }
  const Coupling& g = cfg.coupling;
  cap.metadata = {{"source", "knoblab-discrepancy-bench two-body plant"},
                  {"knob", cfg.knob_name},
                  {"rate_hz", num(cfg.camera.rate_hz)},
                  {"seed", std::to_string(cfg.camera.seed)},
                  {"stimulus", stimulus_json(cfg.stimulus)},
                  {"coupling", "{\"stiffness_Nm_per_rad\": " + (g.rigid() ? std::string("\"rigid\"") : num(g.stiffness)) +
                                   ", \"damping_Nm_s_per_rad\": " + num(g.damping) +
                                   ", \"play_rad\": " + num(g.play) + "}"},
                  {"torque_noise_rms_Nm", num(cfg.camera.torque_noise_rms)},
                  {"encoder_counts_per_rev", std::to_string(cfg.camera.encoder_counts_per_rev)}};
  if (cfg.camera.accelerometer)
    cap.metadata.emplace_back("accelerometer_noise_rms_rad_s2", num(cfg.camera.accelerometer_noise_rms));
  return run;
}

}  // namespace knoblab::bench
