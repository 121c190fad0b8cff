// Small statistics the fits share: quantiles for confidence intervals.
#pragma once

namespace knoblab::fit {

// Φ⁻¹(p) for 0 < p < 1 (Acklam's rational approximation refined by one
// Halley step: |error| < 1e-12). Throws std::domain_error outside (0, 1).
double normal_quantile(double p);

// Student's t quantile for real dof ≥ 1 (Welch–Satterthwaite's are not
// whole): closed forms for 1 and 2 degrees of freedom; otherwise Newton on
// the t distribution function (the regularized incomplete beta function),
// started from the Cornish–Fisher expansion (Abramowitz & Stegun 26.7.5),
// relative error ~1e-13; above 1e5 dof the expansion alone (error O(dof⁻⁵)).
// Throws std::domain_error for dof < 1 (or NaN) or p outside (0, 1).
double student_t_quantile(double p, double dof);

// Half-width of a two-sided 95% interval: t(0.975, dof)·se.
double ci95_half_width(double se, double dof);

}  // namespace knoblab::fit
