#include "sizing.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "knoblab/model/effects.hpp"
#include "knoblab/model/quantile.hpp"
#include "knoblab/sim/coupling.hpp"

namespace knoblab::bench {

std::vector<std::size_t> analysed_rows(const fit::FitData& d, double stick_speed) {
  std::vector<double> speed(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) speed[i] = std::abs(d.omega[i]);
  const double slow = std::max(0.02 * model::quantile(speed, 0.95), stick_speed);
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (speed[i] >= slow) rows.push_back(i);
  return rows;
}

double rms_over(const std::vector<double>& x, const std::vector<std::size_t>& rows) {
  double s = 0.0;
  for (const std::size_t i : rows) s += x[i] * x[i];
  return rows.empty() ? 0.0 : std::sqrt(s / static_cast<double>(rows.size()));
}

namespace {

// The rows discovery keeps for a simulated knob.
std::vector<std::size_t> analysed(const fit::FitData& d, const sim::KnobParams& knob) {
  return analysed_rows(d, knob.stick.dv);
}

// The setting in [lo, hi] (geometric bisection) where `reaches`, monotone
// in it (true toward hi when `increasing`, toward lo otherwise), starts to
// hold; the far end when it never holds.
double boundary(double lo, double hi, bool increasing, int halvings, const std::function<bool(double)>& reaches) {
  const auto above = [&](double s) { return reaches(s) == increasing; };
  if (increasing ? !above(hi) : above(lo)) return increasing ? hi : lo;
  for (int it = 0; it < halvings; ++it) {
    const double mid = std::sqrt(lo * hi);
    (above(mid) ? hi : lo) = mid;
  }
  return increasing ? hi : lo;
}

// The setting in [lo, hi] where the signature's RMS, monotone in it, reaches
// `target`; an end when it does not get there.
double solve(const std::function<std::vector<double>(double)>& signature, const std::vector<std::size_t>& rows,
             double lo, double hi, double target, bool increasing) {
  return boundary(lo, hi, increasing, 40, [&](double s) { return rms_over(signature(s), rows) >= target; });
}

// Coulomb as the knob's sliding law has it (C_pos forward, −C_neg back).
double coulomb(const sim::KnobParams& k, double omega) {
  return omega > 0 ? k.friction.C_pos : omega < 0 ? -k.friction.C_neg : 0.0;
}

}  // namespace

double size_time_delay(const fit::FitData& d, const sim::KnobParams& knob, double target) {
  const auto sig = [&](double delay) {
    const double shift = delay * d.rate_hz;
    std::vector<double> s(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      const double x = std::max(static_cast<double>(i) - shift, 0.0);
      const auto a = static_cast<std::size_t>(x);
      const std::size_t b = std::min(a + 1, d.size() - 1);
      const double late = d.torque[a] + (x - static_cast<double>(a)) * (d.torque[b] - d.torque[a]);
      s[i] = late - d.torque[i];
    }
    return s;
  };
  return solve(sig, analysed(d, knob), 1e-5, 5e-3, target, true);
}

double size_saturation(const fit::FitData& d, const sim::KnobParams& knob, double target) {
  double top = 0.0;
  for (const double t : d.torque) top = std::max(top, std::abs(t));
  const auto sig = [&](double limit) {
    std::vector<double> s(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) s[i] = model::saturate(d.torque[i], limit) - d.torque[i];
    return s;
  };
  return solve(sig, analysed(d, knob), 1e-3 * top, top, target, false);
}

double size_hysteresis(const fit::FitData& d, const sim::KnobParams& knob, double target) {
  const auto sig = [&](double presliding) {
    model::DahlFriction dahl;
    dahl.presliding = presliding;
    dahl.reset(d.omega[0] > 0 ? 1.0 : d.omega[0] < 0 ? -1.0 : 0.0);
    std::vector<double> s(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      const double z = i > 0 ? dahl.update(d.theta[i] - d.theta[i - 1]) : dahl.z;
      s[i] = (z >= 0 ? knob.friction.C_pos : knob.friction.C_neg) * z - coulomb(knob, d.omega[i]);
    }
    return s;
  };
  return solve(sig, analysed(d, knob), 1e-5, 0.03, target, true);
}

double size_backlash(const fit::FitData& d, const sim::KnobParams& knob, double target) {
  const auto sig = [&](double width) {
    model::Backlash play;
    play.width = width;
    play.reset(d.theta[0]);
    std::vector<double> s(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      const double mech = play.update(d.theta[i]);
      const double here = sim::position_torque(knob, d.theta[i], d.omega[i]);
      s[i] = play.contact ? sim::position_torque(knob, mech, d.omega[i]) - here
                          : -(here + knob.friction.torque(d.omega[i]));
    }
    return s;
  };
  return solve(sig, analysed(d, knob), 1e-5, 0.016, target, true);
}

double size_compliance(const std::function<double(double)>& excess, double target) {
  // Each step a capture and a fit: 8 halvings, ≈ 1 % of the log range.
  return boundary(kMinCouplingStiffness, sim::CouplingParams{}.stiffness, false, 8,
                  [&](double k) { return excess(k) >= target; });
}

}  // namespace knoblab::bench
