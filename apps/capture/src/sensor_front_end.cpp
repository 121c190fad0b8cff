#include "knoblab/capture/sensor_front_end.hpp"

#include <algorithm>
#include <stdexcept>

#include "knoblab/model/filters.hpp"

namespace knoblab::capture {

namespace {
// Keep a cutoff well below Nyquist so slow loop rates stay well defined.
model::SosCascade velocity_filter(const SensorConfig& c, double cutoff_hz) {
  return model::design_butterworth_lowpass(c.velocity_filter_order, std::min(cutoff_hz, 0.2 * c.rate_hz),
                                           c.rate_hz);
}
}  // namespace

SensorFrontEnd::SensorFrontEnd(const SensorConfig& cfg)
    : cfg_(cfg),
      dt_(1.0 / cfg.rate_hz),
      velocity_filter_(velocity_filter(cfg, cfg.velocity_cutoff_hz)),
      render_velocity_filter_(velocity_filter(cfg, cfg.render_velocity_cutoff_hz)) {
  if (!(cfg.rate_hz > 0.0)) throw std::invalid_argument("SensorFrontEnd: rate must be positive");
}

const SensorReading& SensorFrontEnd::update(const DaqInputs& in) {
  const SensorCalibration& cal = cfg_.calibration;
  SensorReading& r = reading_;
  r.theta = cal.theta(in.encoder_counts);
  const double raw_omega = have_prev_ ? (r.theta - prev_theta_) / dt_ : 0.0;  // Eq. 1
  have_prev_ = true;
  prev_theta_ = r.theta;
  r.omega = velocity_filter_.process(raw_omega);
  r.omega_render = render_velocity_filter_.process(raw_omega);
  r.accel_V = in.accel_V;
  r.alpha = cal.alpha(in.accel_V, r.theta);
  r.torque = cal.torque(in.torque_V);
  return r;
}

}  // namespace knoblab::capture
