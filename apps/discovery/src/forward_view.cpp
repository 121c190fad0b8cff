#include "forward_view.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace knoblab::discovery::detail {

ForwardError forward_error(const ExtendedModel& m, const fit::FitData& d,
                           std::span<const std::size_t> starts, double horizon_s) {
  ForwardError out;
  const double M = m.base[model::kM_acc];
  if (!(M > 0.0) || d.size() < 3 || !(horizon_s > 0.0)) return out;
  const Layout L = layout_of(m);
  const std::vector<double> p = m.flat();
  const auto base = model::ThesisModel<double>::from_params(p.data());
  const auto steps = static_cast<std::size_t>(std::ceil(horizon_s * d.rate_hz));

  // The windows' rows, gathered first: the operators run over the whole
  // recording once (row_inputs), not once per window.
  std::vector<std::size_t> rows;
  std::size_t next_free = 0;
  for (const std::size_t i0 : starts) {
    if (i0 < next_free || i0 + steps >= d.size()) continue;
    next_free = i0 + steps + 1;
    for (std::size_t k = 0; k <= steps; ++k) rows.push_back(i0 + k);
  }
  const std::vector<RowInputs> in = row_inputs(d, rows, m);
  // Under a time_delay the torque that moved the knob at row i is the one
  // the channel shows δ later.
  const ActiveEffect* delay = m.find(EffectId::TimeDelay);
  const double shift = delay ? delay->setting * d.rate_hz : 0.0;  // samples
  const auto torque_at = [&](std::size_t i) { return value_at(d.torque, static_cast<double>(i) + shift); };
  // Under compliance the model moves the knob, and the encoder reads it plus
  // the coupling's twist, which the measured torque sets (row_inputs).
  const bool twisted = m.has(EffectId::Compliance) && delay == nullptr;
  const auto twist = [&](std::size_t j) { return twisted ? d.theta[rows[j]] - in[j].theta : 0.0; };
  const auto twist_rate = [&](std::size_t j) { return twisted ? d.omega[rows[j]] - in[j].omega : 0.0; };

  double ss_theta = 0.0, ss_omega = 0.0;
  std::size_t count = 0;
  for (std::size_t w = 0; w + steps < rows.size(); w += steps + 1) {
    const std::size_t* window = rows.data() + w;
    double theta = d.theta[window[0]] - twist(w), omega = d.omega[window[0]] - twist_rate(w);
    for (std::size_t k = 1; k <= steps; ++k) {
      RowInputs r = in[w + k - 1];
      r.theta = theta, r.omega = omega, r.alpha = 0.0;  // M·θ̈ is what is integrated
      const double tau_model = extended_torque(L, p.data(), base, r);
      const double accel = (torque_at(window[k - 1]) - tau_model) / M;
      const double h = d.t[window[k]] - d.t[window[k - 1]];
      // The model's damping taken implicitly (linearised backward Euler):
      // with a small M and a slow sample rate (a host PC's 435 Hz), h·B/M
      // passes 2 and an explicit step rings up without bound.
      RowInputs faster = r;
      const double dw = 1e-6 * std::max(1.0, std::abs(omega));
      faster.omega = omega + dw;
      const double damping = std::max(0.0, (extended_torque(L, p.data(), base, faster) - tau_model) / dw);
      const double next = omega + h * accel / (1.0 + h * damping / M);
      // Dry friction stops the knob; it does not push it back through zero.
      omega = (omega != 0.0 && next * omega < 0.0) ? 0.0 : next;
      theta += h * omega;
      const double et = theta + twist(w + k) - d.theta[window[k]];
      const double ew = omega + twist_rate(w + k) - d.omega[window[k]];
      // A knob a radian off within one short window has not been predicted
      // badly, the model runs away (negative damping fitted for a direction
      // the recording never turned): no figure rather than a huge one.
      if (!(std::abs(et) < 1.0)) return ForwardError{};
      ss_theta += et * et;
      ss_omega += ew * ew;
      ++count;
    }
    ++out.windows;
  }
  if (count > 0) {
    out.rms_theta_rad = std::sqrt(ss_theta / static_cast<double>(count));
    out.rms_omega_rad_s = std::sqrt(ss_omega / static_cast<double>(count));
  }
  return out;
}

}  // namespace knoblab::discovery::detail
