// Sensor verification and calibration fits (thesis §2.2.1 and §1.2.3), the
// fits hapticd's Calibrate mode runs. SI units throughout: rad, rad/s,
// rad/s², N·m, volts for the raw accelerometer channel.
//
//   Table 4:  mean and SD of (commanded − measured) for θ, ω, α, τ.
//   Eq. 12:   θ̈_true = C_cal · V_raw, least squares (Matlab's `\`).
//   Eq. 2:    gravity(θ) = A·sin(θ/B + C) + D with B = 1, linear least squares
//             on [sin θ, cos θ, 1] from one slow constant-velocity revolution
//             each way (CW, CCW); the two fits are averaged, which cancels a
//             sensor lag (it shifts the phase by +δ one way and −δ the other).
//
// The fits are built on small accumulators of sufficient statistics (running
// moments, LinearLsq's normal equations). They are trivially copyable and
// never allocate, so the realtime CalibrationController feeds them sample by
// sample; the solving (which may throw) is done by non-realtime code. The
// span functions below are the same fits over recorded data.
//
// Every fitted value comes with a standard error and the half-width of its
// two-sided 95% confidence interval, t(0.975, dof)·se (stats.hpp), with the
// degrees of freedom of that estimate: n − 1 for a Table 4 mean, n − p for a
// regression coefficient, 1 for the gravity amplitude and offset (the spread
// of two directions' estimates).
//
// Too little or degenerate data: the fits throw FitDataError (fit_data.hpp).
#pragma once

#include <cstdint>
#include <span>

#include "knoblab/fit/linear_lsq.hpp"

namespace knoblab::fit {

struct ErrorStats {
  std::int64_t n = 0;
  double mean = 0.0;       // of commanded − measured
  double sd = 0.0;         // sample standard deviation (n − 1)
  double mean_ci95 = 0.0;  // 95% half-width of the mean, t(0.975, n − 1)·sd/√n
};

// Welford's running mean / variance.
class RunningStats {
 public:
  void add(double x) noexcept {
    ++n_;
    const double d = x - mean_;
    mean_ += d / static_cast<double>(n_);
    m2_ += d * (x - mean_);
  }
  std::int64_t count() const noexcept { return n_; }
  // Throws FitDataError for fewer than 2 values.
  ErrorStats stats() const;

 private:
  std::int64_t n_ = 0;
  double mean_ = 0.0, m2_ = 0.0;
};

// Table 4 row set. A channel nobody measured has n = 0.
struct Table4 {
  ErrorStats theta, omega, alpha, torque;
};

// Mean/SD of commanded[i] − measured[i]. Throws FitDataError when the sizes
// differ or there are fewer than 2 values.
ErrorStats error_stats(std::span<const double> commanded, std::span<const double> measured);

// ---- Eq. 12: accelerometer gain ----

struct AccelGainFit {
  double C_cal = 0.0;        // (rad/s²)/V
  double C_cal_se = 0.0;     // standard error (delta method from 1/C_cal's)
  double C_cal_ci95 = 0.0;   // 95% half-width, t(0.975, dof)·C_cal_se
  double residual_sd = 0.0;  // rad/s², of C_cal·V about the fit
  // With gravity terms: the gravity seen meanwhile (Eq. 2, B = 1), rad/s².
  bool with_gravity = false;
  double grav_A = 0.0, grav_C = 0.0, grav_D = 0.0;
  std::int64_t n = 0;
  std::int64_t dof = 0;  // n − 1, or n − 4 with the gravity terms
};

// Eq. 12: α_true = C_cal·V (no intercept), or, with_gravity,
// C_cal·V = α_true + a·sin θ + b·cos θ + D, so that the gravity signal
// cannot bias C_cal whatever the current Eq. 2 constants are.
// The regression runs the other way round from Matlab's `α \ V`: V (noisy,
// the sensor) on α_true (the commanded, noise-free acceleration) for k =
// 1/C_cal. Regressing α on noisy V would attenuate C_cal by the factor
// var(signal)/(var(signal) + var(noise)) — about 1 % low at the simulated
// ADXL202's noise on the spatial sweep.
class AccelGainAccumulator {
 public:
  explicit AccelGainAccumulator(bool with_gravity = true) : with_gravity_(with_gravity) {}
  void add(double volts, double alpha_true, double theta) noexcept;
  std::int64_t count() const noexcept { return with_gravity_ ? full_.count() : plain_.count(); }
  AccelGainFit fit() const;  // throws FitDataError

 private:
  bool with_gravity_;
  LinearLsq<1> plain_{};
  LinearLsq<4> full_{};
};

AccelGainFit fit_accel_gain(std::span<const double> volts, std::span<const double> alpha_true);
AccelGainFit fit_accel_gain(std::span<const double> volts, std::span<const double> alpha_true,
                            std::span<const double> theta);

// ---- Eq. 2: gravity compensation ----

// One direction's fit. The standard errors are the regression's (C's and A's
// by the delta method through a·sin θ + b·cos θ), with dof = n − 3.
struct GravityDirectionFit {
  double A = 0.0, C = 0.0, D = 0.0;  // rad/s², rad, rad/s²
  double A_se = 0.0, C_se = 0.0, D_se = 0.0;
  double residual_sd = 0.0;
  std::int64_t n = 0;
  std::int64_t dof = 0;
};

// The two directions combined. A and D are the means of the directions'
// values (the lag moves neither), and their standard errors are those of a
// mean of two estimates, half their spread: that also covers whatever else
// differs between the directions, at the price of 1 degree of freedom
// (t(0.975, 1) = 12.71). C is the phase of the averaged sin/cos coefficients,
// the bisector of the two directions' phases; their spread is the lag (which
// the average cancels), not noise, so C's standard error comes from the two
// regressions, ½·√(se_cw² + se_ccw²), with Welch–Satterthwaite's dof.
struct GravityFit {
  double A = 0.0, B = 1.0, C = 0.0, D = 0.0;  // Eq. 2, rad/s² (after C_cal)
  double A_se = 0.0, D_se = 0.0;              // half the directions' spread
  double A_ci95 = 0.0, D_ci95 = 0.0;          // t(0.975, 1)·se
  double C_se = 0.0, C_ci95 = 0.0;            // rad, from the regressions
  double C_dof = 0.0;                         // Welch–Satterthwaite, ≈ n_cw + n_ccw − 6
  GravityDirectionFit cw, ccw;                // θ increasing / decreasing
};

// y = C_cal·V − α_true: what the accelerometer reports beyond the motion.
class GravityAccumulator {
 public:
  void add(double theta, double y, bool ccw) noexcept;
  std::int64_t count(bool ccw) const noexcept { return ccw ? ccw_.count() : cw_.count(); }
  GravityFit fit() const;  // throws FitDataError (each direction needs data)

 private:
  LinearLsq<3> cw_{}, ccw_{};
};

GravityFit fit_gravity(std::span<const double> theta_cw, std::span<const double> y_cw,
                       std::span<const double> theta_ccw, std::span<const double> y_ccw);

// A·sin(θ + C) + D with A ≥ 0 and C in (−π, π] from a·sin θ + b·cos θ + D
// (no standard errors).
GravityDirectionFit gravity_from_coefficients(double a, double b, double D);

}  // namespace knoblab::fit
