#include "knoblab/fit/stats.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace knoblab::fit {

double normal_quantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::domain_error("normal_quantile: p must be in (0, 1)");
  // Acklam's coefficients.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,
                                 -2.759285104469687e+02, 1.383577518672690e+02,
                                 -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02,
                                 -1.556989798598866e+02, 6.680131188771972e+01,
                                 -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01,
                                 -2.400758277161838e+00, -2.549732539343734e+00,
                                 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01,
                                 2.445134137142996e+00, 3.754408661907416e+00};
  constexpr double p_low = 0.02425;
  double x;
  if (p < p_low) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p <= 1 - p_low) {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  } else {
    const double q = std::sqrt(-2 * std::log(1 - p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  // One Halley step on Φ(x) − p; above ½ as (1 − p) − Φ(−x), both small and
  // exact enough (1 − p is exact there, while Φ(x) near 1 would round).
  const double e = p <= 0.5 ? 0.5 * std::erfc(-x / std::numbers::sqrt2) - p
                            : (1 - p) - 0.5 * std::erfc(x / std::numbers::sqrt2);
  const double u = e * std::sqrt(2 * std::numbers::pi) * std::exp(x * x / 2);
  return x - u / (1 + x * u / 2);
}

namespace {

// Continued fraction of the regularized incomplete beta function (modified
// Lentz; Numerical Recipes' betacf). Converges for x < (a + 1)/(a + b + 2).
double beta_continued_fraction(double a, double b, double x) {
  constexpr double tiny = 1e-300;
  const double qab = a + b, qap = a + 1, qam = a - 1;
  double c = 1, d = 1 - qab * x / qap;
  if (std::abs(d) < tiny) d = tiny;
  d = 1 / d;
  double h = d;
  for (int m = 1; m <= 10000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1) < 1e-15) break;
  }
  return h;
}

// I_x(a, b), given x and y = 1 − x separately (y is the precise one near x = 1).
double incomplete_beta(double a, double b, double x, double y) {
  if (x <= 0) return 0;
  if (y <= 0) return 1;
  const double log_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log(y);
  if (x < (a + 1) / (a + b + 2)) return std::exp(log_front) * beta_continued_fraction(a, b, x) / a;
  return 1 - std::exp(log_front) * beta_continued_fraction(b, a, y) / b;
}

// P(T > t) for t ≥ 0 with ν degrees of freedom: ½·I_{ν/(ν+t²)}(ν/2, ½).
double t_upper_tail(double t, double nu) {
  if (!(t > 0)) return 0.5;
  const double r = nu / (t * t);  // +inf at t = 0
  return 0.5 * incomplete_beta(nu / 2, 0.5, r / (1 + r), 1 / (1 + r));
}

double t_density(double t, double nu) {
  return std::exp(std::lgamma((nu + 1) / 2) - std::lgamma(nu / 2) - 0.5 * std::log(nu * std::numbers::pi) -
                  (nu + 1) / 2 * std::log1p(t * t / nu));
}

// The Cornish–Fisher expansion (Abramowitz & Stegun 26.7.5) about the normal
// quantile: error O(ν⁻⁵), so exact in double for large ν.
double t_cornish_fisher(double p, double nu) {
  const double z = normal_quantile(p), z2 = z * z;
  const double g1 = (z2 + 1) * z / 4;
  const double g2 = ((5 * z2 + 16) * z2 + 3) * z / 96;
  const double g3 = (((3 * z2 + 19) * z2 + 17) * z2 - 15) * z / 384;
  const double g4 = ((((79 * z2 + 776) * z2 + 1482) * z2 - 1920) * z2 - 945) * z / 92160;
  return z + g1 / nu + g2 / (nu * nu) + g3 / (nu * nu * nu) + g4 / (nu * nu * nu * nu);
}

}  // namespace

double student_t_quantile(double p, double dof) {
  if (!(dof >= 1.0)) throw std::domain_error("student_t_quantile: dof must be >= 1");
  if (!(p > 0.0 && p < 1.0)) throw std::domain_error("student_t_quantile: p must be in (0, 1)");
  if (dof == 1.0) return std::tan(std::numbers::pi * (p - 0.5));
  if (dof == 2.0) {
    const double q = 2 * p - 1;
    return q * std::sqrt(2 / (1 - q * q));
  }
  if (p == 0.5) return 0.0;
  if (dof > 1e5) return t_cornish_fisher(p, dof);
  // Solve P(T > t) = q for t > 0 (the lower half by symmetry): Newton from
  // the Cornish–Fisher value, kept inside a bracket [lo, hi] by bisection.
  const double q = p < 0.5 ? p : 1 - p;
  const double sign = p < 0.5 ? -1.0 : 1.0;
  double lo = 0.0, hi = std::max(1.0, std::abs(t_cornish_fisher(p, dof)));
  while (t_upper_tail(hi, dof) > q && std::isfinite(hi)) {
    lo = hi;
    hi *= 2;
  }
  double t = std::clamp(std::abs(t_cornish_fisher(p, dof)), lo, hi);
  for (int i = 0; i < 200; ++i) {
    const double g = t_upper_tail(t, dof) - q;  // decreasing in t
    if (g > 0)
      lo = t;
    else
      hi = t;
    const double f = t_density(t, dof);
    double next = f > 0 ? t + g / f : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool done = std::abs(next - t) <= 1e-14 * t || hi - lo <= 1e-15 * hi;
    t = next;
    if (done) break;
  }
  return sign * t;
}

double ci95_half_width(double se, double dof) { return student_t_quantile(0.975, dof) * se; }

}  // namespace knoblab::fit
