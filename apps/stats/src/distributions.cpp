#include "knoblab/stats/distributions.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace knoblab::stats {
namespace {

constexpr double kEpsilon = 1e-15;  // relative convergence of series and fractions
constexpr int kMaxIterations = 100000;
constexpr double kTiny = 1e-300;    // keeps Lentz's denominators off zero

void require_dof(double df, const char* what) {
  if (!(df > 0) || !std::isfinite(df))
    throw std::invalid_argument(std::string(what) + ": degrees of freedom must be finite and > 0");
}

void require_not_nan(double x, const char* what) {
  if (std::isnan(x)) throw std::invalid_argument(std::string(what) + ": argument is NaN");
}

// Continued fraction for I_x(a, b) (Numerical Recipes' betacf, modified
// Lentz). It converges fast for x < (a + 1)/(a + b + 2), the only place it
// is called.
double beta_continued_fraction(double a, double b, double x) {
  const double qab = a + b, qap = a + 1, qam = a - 1;
  double c = 1, d = 1 - qab * x / qap;
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1 / d;
  double h = d;
  for (int m = 1; m <= kMaxIterations; ++m) {
    const double m2 = 2.0 * m;
    // Even step, then odd step of the fraction.
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1) < kEpsilon) return h;
  }
  throw std::runtime_error("incomplete_beta: continued fraction did not converge");
}

// I_x(a, b) with y = 1 − x passed separately: callers form y without
// cancellation (e.g. df1·f/(df2 + df1·f)), which keeps upper tails precise.
double incomplete_beta_xy(double a, double b, double x, double y) {
  if (x <= 0) return 0;
  if (y <= 0) return 1;
  const double log_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log(y);
  // Use the fraction where it converges; elsewhere the symmetry
  // I_x(a, b) = 1 − I_y(b, a).
  if (x < (a + 1) / (a + b + 2)) return std::exp(log_front) * beta_continued_fraction(a, b, x) / a;
  return 1 - std::exp(log_front) * beta_continued_fraction(b, a, y) / b;
}

// exp(−x)·x^a/Γ(a), the factor both incomplete gamma expansions share.
double gamma_front(double a, double x) { return std::exp(-x + a * std::log(x) - std::lgamma(a)); }

// P(a, x) by its power series (Numerical Recipes' gser); for x < a + 1.
double gamma_p_series(double a, double x) {
  double ap = a, term = 1 / a, sum = term;
  for (int n = 0; n < kMaxIterations; ++n) {
    ap += 1;
    term *= x / ap;
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEpsilon) return sum * gamma_front(a, x);
  }
  throw std::runtime_error("gamma_p: series did not converge");
}

// Q(a, x) by its continued fraction (Numerical Recipes' gcf, modified
// Lentz); for x ≥ a + 1.
double gamma_q_fraction(double a, double x) {
  double b = x + 1 - a, c = 1 / kTiny, d = 1 / b, h = d;
  for (int i = 1; i <= kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1) < kEpsilon) return h * gamma_front(a, x);
  }
  throw std::runtime_error("gamma_q: continued fraction did not converge");
}

void require_gamma_args(double a, double x, const char* what) {
  if (!(a > 0) || !std::isfinite(a)) throw std::invalid_argument(std::string(what) + ": a must be finite and > 0");
  require_not_nan(x, what);
  if (x < 0) throw std::invalid_argument(std::string(what) + ": x must be >= 0");
}

}  // namespace

double incomplete_beta(double a, double b, double x) {
  if (!(a > 0) || !(b > 0) || !std::isfinite(a) || !std::isfinite(b))
    throw std::invalid_argument("incomplete_beta: a and b must be finite and > 0");
  if (!(x >= 0 && x <= 1)) throw std::invalid_argument("incomplete_beta: x must be in [0, 1]");
  return incomplete_beta_xy(a, b, x, 1 - x);
}

double gamma_p(double a, double x) {
  require_gamma_args(a, x, "gamma_p");
  if (x == 0) return 0;
  if (std::isinf(x)) return 1;
  return x < a + 1 ? gamma_p_series(a, x) : 1 - gamma_q_fraction(a, x);
}

double gamma_q(double a, double x) {
  require_gamma_args(a, x, "gamma_q");
  if (x == 0) return 1;
  if (std::isinf(x)) return 0;
  return x < a + 1 ? 1 - gamma_p_series(a, x) : gamma_q_fraction(a, x);
}

double normal_cdf(double z) {
  require_not_nan(z, "normal_cdf");
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

double normal_sf(double z) {
  require_not_nan(z, "normal_sf");
  return 0.5 * std::erfc(z / std::numbers::sqrt2);
}

double t_two_sided_p(double t, double df) {
  require_dof(df, "t_two_sided_p");
  require_not_nan(t, "t_two_sided_p");
  if (std::isinf(t)) return 0;
  // P(|T| ≥ |t|) = I_{df/(df + t²)}(df/2, 1/2).
  const double t2 = t * t;
  return incomplete_beta_xy(df / 2, 0.5, df / (df + t2), t2 / (df + t2));
}

double t_sf(double t, double df) {
  require_dof(df, "t_sf");
  require_not_nan(t, "t_sf");
  const double half_tail = 0.5 * t_two_sided_p(t, df);
  return t >= 0 ? half_tail : 1 - half_tail;
}

double t_cdf(double t, double df) {
  require_not_nan(t, "t_cdf");
  return t_sf(-t, df);
}

double chi2_cdf(double x, double df) {
  require_dof(df, "chi2_cdf");
  require_not_nan(x, "chi2_cdf");
  return x <= 0 ? 0 : gamma_p(df / 2, x / 2);
}

double chi2_sf(double x, double df) {
  require_dof(df, "chi2_sf");
  require_not_nan(x, "chi2_sf");
  return x <= 0 ? 1 : gamma_q(df / 2, x / 2);
}

double f_cdf(double f, double df1, double df2) {
  require_dof(df1, "f_cdf");
  require_dof(df2, "f_cdf");
  require_not_nan(f, "f_cdf");
  if (f <= 0) return 0;
  if (std::isinf(f)) return 1;
  const double s = df1 * f + df2;
  return incomplete_beta_xy(df1 / 2, df2 / 2, df1 * f / s, df2 / s);
}

double f_sf(double f, double df1, double df2) {
  require_dof(df1, "f_sf");
  require_dof(df2, "f_sf");
  require_not_nan(f, "f_sf");
  if (f <= 0) return 1;
  if (std::isinf(f)) return 0;
  const double s = df1 * f + df2;
  return incomplete_beta_xy(df2 / 2, df1 / 2, df2 / s, df1 * f / s);
}

}  // namespace knoblab::stats
