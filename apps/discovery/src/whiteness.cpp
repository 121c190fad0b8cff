// Residual whiteness and input independence (see whiteness.hpp).
#include "knoblab/discovery/whiteness.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace knoblab::discovery {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// P(a, x) by its power series: converges fast for x < a + 1.
double gamma_p_series(double a, double x) {
  double ap = a, del = 1.0 / a, sum = del;
  for (int n = 0; n < 10000 && std::abs(del) > std::abs(sum) * 1e-16; ++n) {
    ap += 1.0;
    del *= x / ap;
    sum += del;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by its continued fraction (modified Lentz): for x ≥ a + 1, where
// it also keeps the far tail's relative accuracy (1 − P would round to 0).
double gamma_q_fraction(double a, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

double mean_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

std::vector<double> centred(const std::vector<double>& v) {
  const double m = mean_of(v);
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] - m;
  return out;
}

// Σ x(i + k)·y(i) over the pairs inside one run.
double lagged(const std::vector<double>& x, const std::vector<double>& y,
              const std::vector<std::size_t>& run_starts, long k) {
  double sum = 0.0;
  const long n = static_cast<long>(x.size());
  long a = 0;
  for (std::size_t r = 0; r <= run_starts.size(); ++r) {
    const long b = r < run_starts.size() ? static_cast<long>(run_starts[r]) : n;
    for (long i = std::max(a, a - k); i < std::min(b, b - k); ++i)
      sum += x[static_cast<std::size_t>(i + k)] * y[static_cast<std::size_t>(i)];
    a = b;
  }
  return sum;
}

double sum_sq(const std::vector<double>& v) {
  return std::inner_product(v.begin(), v.end(), v.begin(), 0.0);
}

// ρ(0 … K) of x, normalized by Σx² (the biased estimate: a valid
// autocorrelation, which keeps the covariance below positive semidefinite).
std::vector<double> autocorr(const std::vector<double>& x, const std::vector<std::size_t>& runs,
                             std::size_t K) {
  const double s = sum_sq(x);
  std::vector<double> rho(K + 1, 0.0);
  for (std::size_t k = 0; k <= K && s > 0.0; ++k)
    rho[k] = lagged(x, x, runs, static_cast<long>(k)) / s;
  return rho;
}

}  // namespace

double gamma_q(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) return kNaN;
  if (x == 0.0) return 1.0;
  if (std::isinf(x)) return 0.0;
  return x < a + 1.0 ? 1.0 - gamma_p_series(a, x) : gamma_q_fraction(a, x);
}

double chi2_sf(double x, double dof) { return gamma_q(0.5 * dof, 0.5 * x); }

double fit_percent(const std::vector<double>& y, const std::vector<double>& residual) {
  const double spread = std::sqrt(sum_sq(centred(y)));
  if (!(spread > 0.0)) return kNaN;
  return 100.0 * (1.0 - std::sqrt(sum_sq(residual)) / spread);
}

Correlation whiteness(const Series& s, std::size_t max_lag) {
  Correlation c;
  const std::size_t n = s.residual.size();
  c.rows = n;
  c.dof = static_cast<double>(max_lag);
  const double N = static_cast<double>(n);
  c.band = n > 0 ? kBand99 / std::sqrt(N) : kNaN;
  const std::vector<double> e = centred(s.residual);
  if (n < max_lag + 2 || max_lag == 0 || !(sum_sq(e) > 0.0)) {
    c.p = kNaN;
    return c;
  }
  const std::vector<double> rho = autocorr(e, s.run_starts, max_lag);
  for (std::size_t k = 1; k <= max_lag; ++k) {
    c.lags.push_back(static_cast<int>(k));
    c.r.push_back(rho[k]);
    c.statistic += rho[k] * rho[k] / (N - static_cast<double>(k));
  }
  c.statistic *= N * (N + 2.0);  // Ljung–Box Q
  c.p = chi2_sf(c.statistic, c.dof);
  return c;
}

Correlation independence(const Series& s, std::size_t max_lag) {
  Correlation c;
  const std::size_t n = s.residual.size();
  const std::size_t L = max_lag;
  c.rows = n;
  const double N = static_cast<double>(n);
  const std::vector<double> e = centred(s.residual), u = centred(s.input);
  const double see = sum_sq(e), suu = sum_sq(u);
  if (n < 4 * (L + 1) || u.size() != n || !(see > 0.0) || !(suu > 0.0)) {
    c.band = n > 0 ? kBand99 / std::sqrt(N) : kNaN;
    c.p = kNaN;
    return c;
  }
  const long Ll = static_cast<long>(L);
  for (long k = -Ll; k <= Ll; ++k) {
    c.lags.push_back(static_cast<int>(k));
    c.r.push_back(lagged(e, u, s.run_starts, k) / std::sqrt(see * suu));
  }

  // The residual's own autocorrelation: with its part proportional to the
  // input taken out first (nothing, when they are independent; otherwise a
  // smooth input would lend the residual its autocorrelation and widen the
  // band that should reveal the dependence).
  const double beta = std::inner_product(e.begin(), e.end(), u.begin(), 0.0) / suu;
  std::vector<double> own(n);
  for (std::size_t i = 0; i < n; ++i) own[i] = e[i] - beta * u[i];
  // Bartlett window M: until that autocorrelation has stayed inside the
  // white band for L lags (not a mere zero crossing), doubled; at least 2L,
  // at most N/4. A longer window only adds estimation noise.
  const std::size_t kmax = n / 4;
  const std::vector<double> rho_e = autocorr(own, s.run_starts, kmax);
  const double white = kBand99 / std::sqrt(N);
  std::size_t quiet = 0, died = kmax;
  for (std::size_t k = 1; k <= kmax; ++k) {
    quiet = std::abs(rho_e[k]) < white ? quiet + 1 : 0;
    if (quiet >= L) {
      died = k - L + 1;
      break;
    }
  }
  const std::size_t M = std::clamp<std::size_t>(2 * died, 2 * L, std::max(2 * L, kmax));
  const std::vector<double> rho_u = autocorr(u, s.run_starts, M + 2 * L);
  auto at = [](const std::vector<double>& rho, long k) {
    const auto i = static_cast<std::size_t>(std::abs(k));
    return i < rho.size() ? rho[i] : 0.0;
  };
  // C(d) = Σ_j w(j)·ρ_e(j)·ρ_u(j − d), the covariance (×N) of r(k) and r(k + d).
  const long Ml = static_cast<long>(M);
  std::vector<double> cov(2 * L + 1, 0.0);
  for (long d = 0; d <= 2 * Ll; ++d) {
    for (long j = -Ml; j <= Ml; ++j) {
      const double w = 1.0 - static_cast<double>(std::abs(j)) / static_cast<double>(M + 1);
      cov[static_cast<std::size_t>(d)] += w * at(rho_e, j) * at(rho_u, j - d);
    }
  }
  c.band = kBand99 * std::sqrt(std::max(cov[0], 0.0) / N);

  const Eigen::Index K = static_cast<Eigen::Index>(2 * L + 1);
  Eigen::MatrixXd C(K, K);
  Eigen::VectorXd r(K);
  for (Eigen::Index a = 0; a < K; ++a) {
    r(a) = c.r[static_cast<std::size_t>(a)];
    for (Eigen::Index b = 0; b < K; ++b) C(a, b) = cov[static_cast<std::size_t>(std::abs(a - b))];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(C);
  const double top = eig.eigenvalues().maxCoeff();
  const Eigen::VectorXd proj = eig.eigenvectors().transpose() * r;
  for (Eigen::Index k = 0; k < K; ++k) {
    const double lambda = eig.eigenvalues()(k);
    if (!(lambda > 1e-3 * top)) continue;  // direction the lags do not determine
    c.statistic += N * proj(k) * proj(k) / lambda;
    c.dof += 1.0;
  }
  c.p = c.dof > 0.0 ? chi2_sf(c.statistic, c.dof) : kNaN;
  return c;
}

TraceRows figure_rows(const ResidualTrace& tr, std::size_t max_lag) {
  TraceRows out;
  std::vector<std::size_t> held;
  for (std::size_t i = 0; i < tr.size(); ++i)
    if (tr.heldout[i]) held.push_back(i);
  out.heldout = held.size() >= 8 * (max_lag + 1);
  if (out.heldout) {
    out.rows = std::move(held);
  } else {
    out.rows.resize(tr.size());
    std::iota(out.rows.begin(), out.rows.end(), std::size_t{0});
  }
  // Row spacing: median Δt of consecutive rows of the same kind.
  std::vector<double> dt;
  for (std::size_t j = 1; j < out.rows.size(); ++j) {
    const std::size_t a = out.rows[j - 1], b = out.rows[j];
    const double step = tr.t[b] - tr.t[a];
    if (tr.heldout[a] == tr.heldout[b] && step > 0.0) dt.push_back(step);
  }
  if (!dt.empty()) {
    const auto mid = dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2);
    std::nth_element(dt.begin(), mid, dt.end());
    out.row_spacing_s = *mid;
  }
  // A run ends at a gap: a block edge, left-out samples, a change of kind.
  for (std::size_t j = 1; j < out.rows.size(); ++j) {
    const std::size_t a = out.rows[j - 1], b = out.rows[j];
    const double step = tr.t[b] - tr.t[a];
    if (tr.heldout[a] != tr.heldout[b] || !(step > 0.0) || step > 1.5 * out.row_spacing_s)
      out.run_starts.push_back(j);
  }
  return out;
}

ResidualFigures residual_figures(const ResidualTrace& tr, const std::vector<double>& residual,
                                 std::size_t max_lag) {
  ResidualFigures f;
  f.rows = figure_rows(tr, max_lag);
  Series s;
  std::vector<double> y;
  for (const std::size_t i : f.rows.rows) {
    s.residual.push_back(residual[i]);
    s.input.push_back(tr.omega[i]);
    y.push_back(tr.torque[i]);
  }
  s.run_starts = f.rows.run_starts;
  f.fit_percent = fit_percent(y, s.residual);
  f.whiteness = whiteness(s, max_lag);
  f.independence = independence(s, max_lag);
  return f;
}

}  // namespace knoblab::discovery
