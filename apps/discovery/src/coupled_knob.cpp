#include "coupled_knob.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace knoblab::discovery::detail {

namespace {

// Semi-implicit Euler is stable while h·ω_n < 2 and h·c/J < 2; well inside
// that it is also accurate enough for a ringing the 5 kHz camera resolves.
constexpr double kStepFraction = 0.3;
constexpr int kMaxSubsteps = 64;

}  // namespace

CoupledMotion simulate_coupled_knob(std::span<const double> t, std::span<const double> motor_theta,
                                    std::span<const double> motor_omega, const CouplingSpec& coupling,
                                    const KnobDynamics& knob) {
  const std::size_t n = t.size();
  if (motor_theta.size() != n || motor_omega.size() != n)
    throw std::invalid_argument("coupled knob: channels of different lengths");
  if (!(coupling.stiffness > 0.0) || !(knob.inertia > 0.0))
    throw std::invalid_argument("coupled knob: stiffness and inertia must be positive");
  CoupledMotion out;
  for (auto* v : {&out.theta, &out.omega, &out.alpha, &out.torque}) v->assign(n, 0.0);
  out.stuck.assign(n, 0);
  if (n == 0) return out;

  const double J = knob.inertia, k = coupling.stiffness, c = coupling.lag_s * coupling.stiffness;
  const double rate = std::max(std::sqrt(k / J), c / J);
  const auto coupling_torque = [&](double e, double e_rate) { return k * e + c * e_rate; };

  // The knob starts at rest against the motor, the coupling relaxed.
  double th = motor_theta[0], w = 0.0;
  bool stuck = true;
  const auto record = [&](std::size_t i, double alpha) {
    out.theta[i] = th;
    out.omega[i] = w;
    out.alpha[i] = alpha;
    out.torque[i] = coupling_torque(motor_theta[i] - th, motor_omega[i] - w);
    out.stuck[i] = stuck ? 1 : 0;
  };
  record(0, 0.0);

  for (std::size_t i = 1; i < n; ++i) {
    const double dt = t[i] - t[i - 1];
    const int steps = std::clamp(static_cast<int>(std::ceil(dt * rate / kStepFraction)), 1, kMaxSubsteps);
    const double h = dt / steps;
    const double w_start = w;
    for (int s = 0; s < steps; ++s) {
      // Motor and knob at the substep's start: the twist of one instant (a
      // knob a substep behind the motor would read h·ω of twist).
      const double f = static_cast<double>(s) / steps;
      const double thm = motor_theta[i - 1] + f * (motor_theta[i] - motor_theta[i - 1]);
      const double wm = motor_omega[i - 1] + f * (motor_omega[i] - motor_omega[i - 1]);
      const double tau = coupling_torque(thm - th, wm - w);
      if (stuck) {
        const double net = tau - knob.torque(th, 0.0);
        if (std::abs(net) <= knob.breakaway) continue;
        stuck = false;  // breaks away toward the net torque, from kinetic friction on
        w = std::copysign(1e-12, net);
      }
      const double w_next = w + h * (tau - knob.torque(th, w)) / J;
      if (w != 0.0 && w_next * w < 0.0) {
        w = 0.0;  // dry friction stops the knob; the next substep tests whether it stays
        stuck = true;
      } else {
        w = w_next;
      }
      th += h * w;
    }
    record(i, (w - w_start) / dt);
  }
  return out;
}

}  // namespace knoblab::discovery::detail
