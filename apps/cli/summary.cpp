#include "summary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "knoblab/model/periodogram.hpp"

namespace knoblab::cli {

CaptureSummary summarize(const interchange::Capture& c) {
  CaptureSummary s;
  s.samples = c.size();
  if (s.samples == 0) return s;
  s.duration_s = c.t.back() - c.t.front();
  s.mean_rate_hz = s.samples > 1 ? static_cast<double>(s.samples - 1) / s.duration_s : 0.0;
  const auto [tmin, tmax] = std::minmax_element(c.theta.begin(), c.theta.end());
  s.theta_min = *tmin;
  s.theta_max = *tmax;
  const auto [qmin, qmax] = std::minmax_element(c.torque.begin(), c.torque.end());
  s.torque_min = *qmin;
  s.torque_max = *qmax;
  double sq = 0;
  for (double q : c.torque) sq += q * q;
  s.torque_rms = std::sqrt(sq / static_cast<double>(s.samples));
  for (double w : c.omega) s.omega_max_abs = std::max(s.omega_max_abs, std::abs(w));

  // A period is only resolvable if the knob travelled at least one of it.
  const double travel = s.theta_max - s.theta_min;
  const double f_min = std::max(1.0, 2.0 * std::numbers::pi / std::max(travel, 1e-9));
  if (f_min < 64.0 && s.samples >= 16) {
    const auto pg = model::angular_periodogram(c.theta, c.torque, f_min, 64.0, 0.05);
    s.detent_cycles_per_rev = pg.peak.frequency;
    s.detent_amplitude = pg.peak.amplitude;
    s.detent_power = pg.peak.power;
  }
  return s;
}

}  // namespace knoblab::cli
