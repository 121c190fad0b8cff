#include "knoblab/hapticd/calibration_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace knoblab::hapticd {

ErrorStats RunningStats::stats() const {
  if (n_ < 2) throw FitError("error statistics need at least 2 samples, got " + std::to_string(n_));
  return {n_, mean_, std::sqrt(m2_ / static_cast<double>(n_ - 1))};
}

ErrorStats error_stats(std::span<const double> commanded, std::span<const double> measured) {
  if (commanded.size() != measured.size()) throw FitError("error statistics: commanded and measured sizes differ");
  RunningStats r;
  for (std::size_t i = 0; i < commanded.size(); ++i) r.add(commanded[i] - measured[i]);
  return r.stats();
}

template <std::size_t N>
typename LinearLsq<N>::Solution LinearLsq<N>::solve() const {
  if (n_ <= static_cast<std::int64_t>(N) + 1)
    throw FitError("least squares with " + std::to_string(N) + " parameters needs more than " +
                   std::to_string(N + 1) + " samples, got " + std::to_string(n_));
  // Gauss–Jordan with partial pivoting on [XᵀX | I].
  std::array<std::array<double, 2 * N>, N> m{};
  double scale = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = 0; j < N; ++j) m[i][j] = xtx_[i][j];
    m[i][N + i] = 1.0;
    scale = std::max(scale, std::abs(xtx_[i][i]));
  }
  if (!(scale > 0.0) || !std::isfinite(scale)) throw FitError("least squares: the data carry no signal");
  for (std::size_t c = 0; c < N; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < N; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    if (std::abs(m[p][c]) <= 1e-12 * scale)
      throw FitError("least squares: the design is singular (the data do not determine every parameter)");
    std::swap(m[p], m[c]);
    const double inv = 1.0 / m[c][c];
    for (double& v : m[c]) v *= inv;
    for (std::size_t r = 0; r < N; ++r) {
      if (r == c) continue;
      const double f = m[r][c];
      for (std::size_t j = 0; j < 2 * N; ++j) m[r][j] -= f * m[c][j];
    }
  }
  Solution s;
  s.n = n_;
  for (std::size_t i = 0; i < N; ++i) {
    double b = 0.0;
    for (std::size_t j = 0; j < N; ++j) b += m[i][N + j] * xty_[j];
    s.beta[i] = b;
  }
  // RSS = yᵀy − 2βᵀXᵀy + βᵀXᵀXβ = yᵀy − βᵀXᵀy at the optimum.
  double bty = 0.0;
  for (std::size_t i = 0; i < N; ++i) bty += s.beta[i] * xty_[i];
  const double rss = std::max(0.0, yty_ - bty);
  const double sigma2 = rss / static_cast<double>(n_ - static_cast<std::int64_t>(N));
  s.residual_sd = std::sqrt(sigma2);
  for (std::size_t i = 0; i < N; ++i) s.se[i] = std::sqrt(std::max(0.0, sigma2 * m[i][N + i]));
  return s;
}

template class LinearLsq<1>;
template class LinearLsq<3>;
template class LinearLsq<4>;

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
  auto gain = [&f](double k, double k_se, double residual_sd_V, std::int64_t n) {
    if (!(std::abs(k) > 0.0) || !std::isfinite(k))
      throw FitError("accelerometer gain: the volts do not follow the acceleration");
    f.C_cal = 1.0 / k;
    f.C_cal_se = k_se / (k * k);  // delta method
    f.residual_sd = residual_sd_V * std::abs(f.C_cal);
    f.n = n;
  };
  if (with_gravity_) {
    const auto s = full_.solve();
    gain(s.beta[0], s.se[0], s.residual_sd, s.n);
    const GravityDirectionFit g =
        gravity_from_coefficients(s.beta[1] * f.C_cal, s.beta[2] * f.C_cal, s.beta[3] * f.C_cal);
    f.grav_A = g.A;
    f.grav_C = g.C;
    f.grav_D = g.D;
  } else {
    const auto s = plain_.solve();
    gain(s.beta[0], s.se[0], s.residual_sd, s.n);
  }
  return f;
}

AccelGainFit fit_accel_gain(std::span<const double> volts, std::span<const double> alpha_true) {
  if (volts.size() != alpha_true.size()) throw FitError("accelerometer gain: sizes differ");
  AccelGainAccumulator acc(false);
  for (std::size_t i = 0; i < volts.size(); ++i) acc.add(volts[i], alpha_true[i], 0.0);
  return acc.fit();
}

AccelGainFit fit_accel_gain(std::span<const double> volts, std::span<const double> alpha_true,
                            std::span<const double> theta) {
  if (volts.size() != alpha_true.size() || volts.size() != theta.size())
    throw FitError("accelerometer gain: sizes differ");
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

void GravityAccumulator::add(double theta, double y, bool ccw) noexcept {
  (ccw ? ccw_ : cw_).add({std::sin(theta), std::cos(theta), 1.0}, y);
}

GravityFit GravityAccumulator::fit() const {
  if (cw_.count() == 0 || ccw_.count() == 0)
    throw FitError("gravity fit needs a rotation in each direction (CW and CCW)");
  const auto s1 = cw_.solve();
  const auto s2 = ccw_.solve();
  GravityFit f;
  f.cw = gravity_from_coefficients(s1.beta[0], s1.beta[1], s1.beta[2]);
  f.cw.residual_sd = s1.residual_sd;
  f.cw.n = s1.n;
  f.ccw = gravity_from_coefficients(s2.beta[0], s2.beta[1], s2.beta[2]);
  f.ccw.residual_sd = s2.residual_sd;
  f.ccw.n = s2.n;
  const GravityDirectionFit avg = gravity_from_coefficients(0.5 * (s1.beta[0] + s2.beta[0]),
                                                            0.5 * (s1.beta[1] + s2.beta[1]),
                                                            0.5 * (s1.beta[2] + s2.beta[2]));
  f.A = avg.A;
  f.B = 1.0;
  f.C = avg.C;
  f.D = avg.D;
  // Two estimates: the standard error of their mean is half their spread.
  f.A_se = 0.5 * std::abs(f.cw.A - f.ccw.A);
  f.D_se = 0.5 * std::abs(f.cw.D - f.ccw.D);
  return f;
}

GravityFit fit_gravity(std::span<const double> theta_cw, std::span<const double> y_cw,
                       std::span<const double> theta_ccw, std::span<const double> y_ccw) {
  if (theta_cw.size() != y_cw.size() || theta_ccw.size() != y_ccw.size())
    throw FitError("gravity fit: sizes differ");
  GravityAccumulator acc;
  for (std::size_t i = 0; i < theta_cw.size(); ++i) acc.add(theta_cw[i], y_cw[i], false);
  for (std::size_t i = 0; i < theta_ccw.size(); ++i) acc.add(theta_ccw[i], y_ccw[i], true);
  return acc.fit();
}

}  // namespace knoblab::hapticd
