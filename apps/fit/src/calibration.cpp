#include "knoblab/fit/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/stats.hpp"

namespace knoblab::fit {

ErrorStats RunningStats::stats() const {
  if (n_ < 2) throw FitDataError("error statistics need at least 2 samples, got " + std::to_string(n_));
  const double n = static_cast<double>(n_);
  const double sd = std::sqrt(m2_ / (n - 1.0));
  return {n_, mean_, sd, ci95_half_width(sd / std::sqrt(n), n - 1.0)};
}

ErrorStats error_stats(std::span<const double> commanded, std::span<const double> measured) {
  if (commanded.size() != measured.size())
    throw FitDataError("error statistics: commanded and measured sizes differ");
  RunningStats r;
  for (std::size_t i = 0; i < commanded.size(); ++i) r.add(commanded[i] - measured[i]);
  return r.stats();
}

// ---- Eq. 12 ----

void AccelGainAccumulator::add(double volts, double alpha_true, double theta) noexcept {
  // V = k·α_true (+ [a'·sin θ + b'·cos θ + D']) with k = 1/C_cal: the noise is
  // on the sensor's side, so V is the regressand (see the header).
  if (with_gravity_)
    full_.add({alpha_true, std::sin(theta), std::cos(theta), 1.0}, volts);
  else
    plain_.add({alpha_true}, volts);
}

AccelGainFit AccelGainAccumulator::fit() const {
  AccelGainFit f;
  f.with_gravity = with_gravity_;
  auto gain = [&f](double k, double k_se, double residual_sd_V, std::int64_t n, std::int64_t dof) {
    if (!(std::abs(k) > 0.0) || !std::isfinite(k))
      throw FitDataError("accelerometer gain: the volts do not follow the acceleration");
    f.C_cal = 1.0 / k;
    f.C_cal_se = k_se / (k * k);  // delta method
    f.C_cal_ci95 = ci95_half_width(f.C_cal_se, static_cast<double>(dof));
    f.residual_sd = residual_sd_V * std::abs(f.C_cal);
    f.n = n;
    f.dof = dof;
  };
  if (with_gravity_) {
    const auto s = full_.solve();
    gain(s.beta[0], s.se[0], s.residual_sd, s.n, s.dof);
    const GravityDirectionFit g =
        gravity_from_coefficients(s.beta[1] * f.C_cal, s.beta[2] * f.C_cal, s.beta[3] * f.C_cal);
    f.grav_A = g.A;
    f.grav_C = g.C;
    f.grav_D = g.D;
  } else {
    const auto s = plain_.solve();
    gain(s.beta[0], s.se[0], s.residual_sd, s.n, s.dof);
  }
  return f;
}

AccelGainFit fit_accel_gain(std::span<const double> volts, std::span<const double> alpha_true) {
  if (volts.size() != alpha_true.size()) throw FitDataError("accelerometer gain: sizes differ");
  AccelGainAccumulator acc(false);
  for (std::size_t i = 0; i < volts.size(); ++i) acc.add(volts[i], alpha_true[i], 0.0);
  return acc.fit();
}

AccelGainFit fit_accel_gain(std::span<const double> volts, std::span<const double> alpha_true,
                            std::span<const double> theta) {
  if (volts.size() != alpha_true.size() || volts.size() != theta.size())
    throw FitDataError("accelerometer gain: sizes differ");
  AccelGainAccumulator acc(true);
  for (std::size_t i = 0; i < volts.size(); ++i) acc.add(volts[i], alpha_true[i], theta[i]);
  return acc.fit();
}

// ---- Eq. 2 ----

GravityDirectionFit gravity_from_coefficients(double a, double b, double D) {
  // A·sin(θ + C) = A·cos C·sin θ + A·sin C·cos θ.
  GravityDirectionFit g;
  g.A = std::hypot(a, b);
  g.C = g.A > 0.0 ? std::atan2(b, a) : 0.0;
  g.D = D;
  return g;
}

namespace {

// One direction's fit with its standard errors: (A, C) = polar(a, b), by the
// delta method through the coefficients' covariance.
GravityDirectionFit gravity_direction(const LinearLsq<3>::Solution& s) {
  const double a = s.beta[0], b = s.beta[1];
  GravityDirectionFit g = gravity_from_coefficients(a, b, s.beta[2]);
  const double vaa = s.cov[0][0], vbb = s.cov[1][1], vab = s.cov[0][1];
  if (g.A > 0.0) {
    const double A2 = g.A * g.A;
    g.A_se = std::sqrt(std::max(0.0, (a * a * vaa + 2.0 * a * b * vab + b * b * vbb) / A2));
    g.C_se = std::sqrt(std::max(0.0, (b * b * vaa - 2.0 * a * b * vab + a * a * vbb) / (A2 * A2)));
  } else {
    g.A_se = std::sqrt(std::max(0.0, 0.5 * (vaa + vbb)));
    g.C_se = std::numbers::pi;  // no amplitude: the phase is undetermined
  }
  g.D_se = s.se[2];
  g.residual_sd = s.residual_sd;
  g.n = s.n;
  g.dof = s.dof;
  return g;
}

}  // namespace

void GravityAccumulator::add(double theta, double y, bool ccw) noexcept {
  (ccw ? ccw_ : cw_).add({std::sin(theta), std::cos(theta), 1.0}, y);
}

GravityFit GravityAccumulator::fit() const {
  if (cw_.count() == 0 || ccw_.count() == 0)
    throw FitDataError("gravity fit needs a rotation in each direction (CW and CCW)");
  const auto s1 = cw_.solve();
  const auto s2 = ccw_.solve();
  GravityFit f;
  f.cw = gravity_direction(s1);
  f.ccw = gravity_direction(s2);
  // The phase: of the averaged coefficients, which bisects the two directions'
  // phases and so cancels a lag.
  f.C = gravity_from_coefficients(0.5 * (s1.beta[0] + s2.beta[0]), 0.5 * (s1.beta[1] + s2.beta[1]), 0.0).C;
  f.B = 1.0;
  // Amplitude and offset: the mean of the two directions' (the averaged
  // coefficients' amplitude would be A·cos δ for a lag δ). Two estimates: the
  // standard error of their mean is half their spread, with 1 dof.
  f.A = 0.5 * (f.cw.A + f.ccw.A);
  f.D = 0.5 * (f.cw.D + f.ccw.D);
  f.A_se = 0.5 * std::abs(f.cw.A - f.ccw.A);
  f.D_se = 0.5 * std::abs(f.cw.D - f.ccw.D);
  f.A_ci95 = ci95_half_width(f.A_se, 1.0);
  f.D_ci95 = ci95_half_width(f.D_se, 1.0);
  // C's standard error from the regressions; Welch–Satterthwaite's dof for
  // the sum of two variances estimated with n − 3 dof each.
  const double v1 = f.cw.C_se * f.cw.C_se, v2 = f.ccw.C_se * f.ccw.C_se;
  const double nu1 = static_cast<double>(f.cw.dof), nu2 = static_cast<double>(f.ccw.dof);
  const double den = v1 * v1 / nu1 + v2 * v2 / nu2;
  f.C_dof = den > 0.0 ? std::min(nu1 + nu2, (v1 + v2) * (v1 + v2) / den) : nu1 + nu2;
  f.C_se = 0.5 * std::sqrt(v1 + v2);
  f.C_ci95 = ci95_half_width(f.C_se, f.C_dof);
  return f;
}

GravityFit fit_gravity(std::span<const double> theta_cw, std::span<const double> y_cw,
                       std::span<const double> theta_ccw, std::span<const double> y_ccw) {
  if (theta_cw.size() != y_cw.size() || theta_ccw.size() != y_ccw.size())
    throw FitDataError("gravity fit: sizes differ");
  GravityAccumulator acc;
  for (std::size_t i = 0; i < theta_cw.size(); ++i) acc.add(theta_cw[i], y_cw[i], false);
  for (std::size_t i = 0; i < theta_ccw.size(); ++i) acc.add(theta_ccw[i], y_ccw[i], true);
  return acc.fit();
}

}  // namespace knoblab::fit
