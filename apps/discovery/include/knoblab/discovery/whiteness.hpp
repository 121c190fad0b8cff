// Residual tests as MATLAB's resid shows them: is the residual white (its
// autocorrelation, Ljung–Box), and is it independent of the input (its
// cross-correlation with the velocity ω)? Plus fit % as MATLAB's compare.
//
//   const ResidualFigures f = residual_figures(r.trace, r.trace.after);
//   f.whiteness.p, f.independence.p, f.fit_percent, f.row_spacing_s
//
// Lags are in trace rows, not samples: the trace is an evenly strided subset
// of each time block, so one lag is row_spacing_s (the median Δt between
// consecutive rows of the same kind). Pairs of rows never span a gap (a block
// edge, left-out slow samples, the change from training to held-out rows).
#pragma once

#include <cstddef>
#include <vector>

#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::discovery {

inline constexpr std::size_t kDefaultMaxLag = 25;  // resid's default
inline constexpr double kBand99 = 2.5758293035489;  // two-sided 99 % normal quantile

// A sequence of consecutive rows cut into runs: lag pairs stay inside a run.
struct Series {
  std::vector<double> residual, input;
  std::vector<std::size_t> run_starts;  // first row of each run after the first
};

struct Correlation {
  std::vector<int> lags;     // in rows
  std::vector<double> r;     // normalized correlation at each lag
  double band = 0.0;         // 99 % band half-width of r when there is no dependence
  double statistic = 0.0;    // portmanteau statistic, χ² under that hypothesis
  double dof = 0.0;
  double p = 1.0;            // its upper-tail probability (NaN: too few rows)
  std::size_t rows = 0;
};

// Autocorrelation for lags 1…L; band ±2.576/√N; Ljung–Box Q with L dof.
Correlation whiteness(const Series& s, std::size_t max_lag = kDefaultMaxLag);

// Cross-correlation r(k) = corr(residual(t+k), input(t)) for k = −L…L.
// Band and test allow for the residual's own autocorrelation (Bartlett:
// var r(k) = Σ_m ρ_e(m)·ρ_u(m)/N, which is 1/N for a white residual, the
// plain ±2.576/√N then; ρ_e of the residual less its part proportional to
// ω): without that, any smooth residual beside a smooth ω would "depend"
// on it. Neighbouring lags of a smooth ω carry nearly the
// same information, so the statistic is rᵀC⁻¹r·N over the well-determined
// directions of their covariance C, dof = their number.
Correlation independence(const Series& s, std::size_t max_lag = kDefaultMaxLag);

// 100·(1 − ‖y − ŷ‖ / ‖y − mean(y)‖), as MATLAB's compare.
double fit_percent(const std::vector<double>& y, const std::vector<double>& residual);

// Regularized upper incomplete gamma Q(a, x), and the χ² upper tail
// P(X > x) for `dof` degrees of freedom (= Q(dof/2, x/2)).
double gamma_q(double a, double x);
double chi2_sf(double x, double dof);

// The trace rows the figures use: held-out rows when there are enough
// (at least 8·(L+1)), else all rows; cut into runs at gaps.
struct TraceRows {
  std::vector<std::size_t> rows;
  std::vector<std::size_t> run_starts;  // positions in `rows`
  bool heldout = false;
  double row_spacing_s = 0.0;           // median Δt of consecutive rows
};
TraceRows figure_rows(const ResidualTrace& tr, std::size_t max_lag = kDefaultMaxLag);

struct ResidualFigures {
  TraceRows rows;
  double fit_percent = 0.0;
  Correlation whiteness, independence;
};

// `residual` is tr.before or tr.after (one value per trace row).
ResidualFigures residual_figures(const ResidualTrace& tr, const std::vector<double>& residual,
                                 std::size_t max_lag = kDefaultMaxLag);

}  // namespace knoblab::discovery
