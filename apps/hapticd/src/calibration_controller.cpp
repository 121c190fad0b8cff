#include "knoblab/hapticd/calibration_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/interchange/sample.hpp"

namespace knoblab::hapticd {

const char* to_string(CalibrationKind k) {
  switch (k) {
    case CalibrationKind::Spatial: return "spatial";
    case CalibrationKind::Torque: return "torque";
    case CalibrationKind::AccelGain: return "accel_gain";
    case CalibrationKind::Gravity: return "gravity";
  }
  return "?";
}

std::optional<CalibrationKind> parse_calibration_kind(std::string_view s) {
  if (s == "spatial") return CalibrationKind::Spatial;
  if (s == "torque") return CalibrationKind::Torque;
  if (s == "accel_gain") return CalibrationKind::AccelGain;
  if (s == "gravity") return CalibrationKind::Gravity;
  return std::nullopt;
}

namespace {

bool positive(double x) { return x > 0.0 && std::isfinite(x); }

double gravity_leg_seconds(const CalibrationConfig& c) {
  // ramp up, settle (as long as the ramp), one fitted revolution, ramp down
  return 3.0 * c.gravity_ramp_seconds + c.gravity_seconds;
}

}  // namespace

CalibrationController::CalibrationController(const CalibrationConfig& cfg) : cfg_(cfg), pid_(cfg.pid) {
  if (!positive(cfg_.rate_hz)) throw std::invalid_argument("calibration: rate must be positive");
  double seconds = 0.0;
  switch (cfg_.kind) {
    case CalibrationKind::Spatial:
    case CalibrationKind::AccelGain:
      stimulus_ = model::SweptSine::spatial();
      seconds = cfg_.sweep_seconds;
      break;
    case CalibrationKind::Torque:
      stimulus_ = model::SweptSine::torque_test();
      seconds = cfg_.sweep_seconds;
      break;
    case CalibrationKind::Gravity:
      if (!positive(cfg_.gravity_seconds) || !(cfg_.gravity_ramp_seconds >= 0.0))
        throw std::invalid_argument("calibration: gravity needs seconds > 0 and ramp >= 0");
      seconds = 2.0 * gravity_leg_seconds(cfg_);
      break;
  }
  if (!positive(seconds)) throw std::invalid_argument("calibration: duration must be positive");
  total_cycles_ = static_cast<std::int64_t>(std::llround(seconds * cfg_.rate_hz));
  if (total_cycles_ < 1) throw std::invalid_argument("calibration: the run is shorter than one cycle");
  data_.kind = cfg_.kind;
  data_.calibration = cfg_.calibration;
}

CalibrationController::Reference CalibrationController::reference(double t) const {
  Reference r;
  if (cfg_.kind != CalibrationKind::Gravity) {
    r.theta = stimulus_.theta(t);
    r.omega = stimulus_.omega(t);
    r.alpha = stimulus_.alpha(t);
    r.fit = true;
    return r;
  }
  // Two legs, +ω₀ then −ω₀, each: linear ramp up over R, hold for R + T,
  // linear ramp down over R. The fitted window is the last T of the hold:
  // exactly one revolution.
  const double R = cfg_.gravity_ramp_seconds, T = cfg_.gravity_seconds;
  const double w0 = 2.0 * std::numbers::pi / T;
  const double leg = gravity_leg_seconds(cfg_);
  // Angle covered by one full leg.
  const double leg_angle = w0 * (R + (R + T));  // two half-ramps + hold
  const bool second = t >= leg;
  const double tl = std::clamp(second ? t - leg : t, 0.0, leg);
  const double sign = second ? -1.0 : 1.0;
  double th = 0.0, w = 0.0, a = 0.0;
  if (R > 0.0 && tl < R) {
    a = w0 / R;
    w = a * tl;
    th = 0.5 * a * tl * tl;
  } else if (tl < 2.0 * R + T) {
    w = w0;
    th = 0.5 * w0 * R + w0 * (tl - R);
  } else {
    const double td = tl - (2.0 * R + T);
    a = -w0 / R;
    w = w0 + a * td;
    th = 0.5 * w0 * R + w0 * (R + T) + w0 * td + 0.5 * a * td * td;
  }
  r.theta = (second ? leg_angle : 0.0) + sign * th;
  r.omega = sign * w;
  r.alpha = sign * a;
  r.fit = tl >= 2.0 * R && tl < 2.0 * R + T;
  r.ccw = second;
  return r;
}

void CalibrationController::update(const capture::SensorReading& in, capture::DaqOutputs& out,
                                   capture::Sample& s) {
  const double dt = 1.0 / cfg_.rate_hz;
  const double t = static_cast<double>(cycle_) * dt;
  const capture::SensorCalibration& cal = cfg_.calibration;

  s.t = t;
  s.theta = in.theta;
  if (cycle_ == 0) data_.theta0 = s.theta;
  s.omega = in.omega;
  s.alpha = in.alpha;
  s.torque = in.torque;

  const Reference ref = reference(t);
  const double ref_theta = data_.theta0 + ref.theta;
  s.command = pid_.update(ref_theta, ref.omega, s.theta, s.omega, dt);
  out.motor_command_V = s.command;
  out.amp_enable = true;

  switch (cfg_.kind) {
    case CalibrationKind::Spatial:
    case CalibrationKind::AccelGain:
      data_.theta.add(ref_theta - s.theta);
      data_.omega.add(ref.omega - s.omega);
      data_.alpha.add(ref.alpha - s.alpha);
      data_.accel.add(in.accel_V, ref.alpha, s.theta);
      break;
    case CalibrationKind::Torque:
      // The command of the previous cycle acted during this one (ZOH).
      if (cycle_ > 0) data_.torque.add(last_command_V_ * cfg_.torque_per_volt - s.torque);
      break;
    case CalibrationKind::Gravity:
      data_.theta.add(ref_theta - s.theta);
      data_.omega.add(ref.omega - s.omega);
      if (ref.fit) data_.gravity.add(s.theta, cal.C_cal * in.accel_V - ref.alpha, ref.ccw);
      break;
  }
  ++cycle_;
}

void CalibrationController::after_output(const capture::DaqOutputs& out, std::uint32_t flags) {
  last_command_V_ = out.amp_enable ? out.motor_command_V : 0.0;
  data_.flags_seen |= flags;
}

CalibrationData CalibrationController::data() const {
  CalibrationData d = data_;
  d.cycles = cycle_;
  d.complete = cycle_ >= total_cycles_ && total_cycles_ > 0;
  return d;
}

namespace {
constexpr double kMaxRelativeGainCi = 0.5;
}  // namespace

CalibrationResult evaluate(const CalibrationData& d) {
  CalibrationResult r;
  r.kind = d.kind;
  r.complete = d.complete;
  r.cycles = d.cycles;
  r.fault = (d.flags_seen & interchange::kFaultLatched) != 0;
  r.torque_limited = (d.flags_seen & interchange::kTorqueLimited) != 0;
  r.in_use = d.calibration;
  r.updated = d.calibration;
  auto stats = [](const fit::RunningStats& s) { return s.count() >= 2 ? s.stats() : fit::ErrorStats{}; };
  r.table4 = {stats(d.theta), stats(d.omega), stats(d.alpha), stats(d.torque)};
  try {
    if (d.kind == CalibrationKind::AccelGain) {
      r.accel = d.accel.fit();
      r.updated.C_cal = r.accel->C_cal;
      // A gain is positive, and one known only to within ±50 % (95 %) is not
      // a calibration: the run did not accelerate the shaft enough. (Runs on
      // the simulated camera give ±5–20 %; the average of three is the
      // calibration, and its spread is reported.)
      if (!(r.accel->C_cal > 0.0) || r.accel->C_cal_ci95 > kMaxRelativeGainCi * r.accel->C_cal)
        throw fit::FitDataError("C_cal = " + std::to_string(r.accel->C_cal) + " ± " +
                                std::to_string(r.accel->C_cal_ci95) +
                                " (95 %) is not a usable gain: the run did not accelerate the shaft enough; "
                                "use the Table 3 sweep (sweep_seconds 5)");
    } else if (d.kind == CalibrationKind::Gravity) {
      r.gravity = d.gravity.fit();
      r.updated.grav_A = r.gravity->A;
      r.updated.grav_B = 1.0;
      r.updated.grav_C = r.gravity->C;
      r.updated.grav_D = r.gravity->D;
    } else {
      const fit::ErrorStats& first = d.kind == CalibrationKind::Torque ? r.table4.torque : r.table4.theta;
      if (first.n < 2) throw fit::FitDataError("the run recorded too few samples for statistics");
    }
  } catch (const fit::FitDataError& e) {
    r.error = e.what();
  }
  if (r.error.empty() && !r.complete) r.error = "the run was stopped before it finished";
  if (r.error.empty() && r.fault) r.error = "a fault latched during the run (outputs were forced safe)";
  // Fits against the reference motion are only as good as the tracking: a
  // clipped command means the shaft did not follow it.
  if (r.error.empty() && r.torque_limited &&
      (d.kind == CalibrationKind::AccelGain || d.kind == CalibrationKind::Gravity))
    r.error = "the torque limit clipped the command, so the shaft did not follow the reference; "
              "use a longer sweep (sweep_seconds) or revolution (gravity_seconds)";
  return r;
}

}  // namespace knoblab::hapticd
