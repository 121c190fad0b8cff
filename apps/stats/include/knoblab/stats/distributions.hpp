// The distribution functions the tests' p-values come from. Survival
// functions (upper tails) are computed directly, not as 1 − cdf, so small
// p-values keep their relative precision.
//
// Every function throws std::invalid_argument for a non-positive or
// non-finite degree of freedom and for a NaN argument.
#pragma once

namespace knoblab::stats {

// Regularized incomplete beta function I_x(a, b) for a, b > 0, 0 ≤ x ≤ 1.
double incomplete_beta(double a, double b, double x);

// Regularized incomplete gamma functions for a > 0, x ≥ 0:
// P(a, x) = γ(a, x)/Γ(a) and its complement Q(a, x) = 1 − P(a, x).
double gamma_p(double a, double x);
double gamma_q(double a, double x);

// Standard normal.
double normal_cdf(double z);
double normal_sf(double z);

// Student's t with df degrees of freedom (real df > 0).
double t_cdf(double t, double df);
double t_sf(double t, double df);
// P(|T| ≥ |t|).
double t_two_sided_p(double t, double df);

// Chi-square with df degrees of freedom.
double chi2_cdf(double x, double df);
double chi2_sf(double x, double df);

// Fisher's F with (df1, df2) degrees of freedom; real dfs, as the
// Greenhouse–Geisser correction makes them.
double f_cdf(double f, double df1, double df2);
double f_sf(double f, double df1, double df2);

}  // namespace knoblab::stats
