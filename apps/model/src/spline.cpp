// Cubic spline construction from the second-derivative (moment) equations
//   h[i-1]·M[i-1] + 2(h[i-1]+h[i])·M[i] + h[i]·M[i+1] = 6(Δ[i] − Δ[i-1]),
// Δ[i] = (y[i+1]−y[i])/h[i]: tridiagonal for natural ends (M = 0 there),
// cyclic tridiagonal for periodic ones.
#include <stdexcept>

#include "knoblab/model/spline.hpp"

namespace knoblab::model {
namespace {

// Thomas algorithm; sub[0] and sup[n-1] are ignored.
std::vector<double> solve_tridiagonal(const std::vector<double>& sub,
                                      const std::vector<double>& diag,
                                      const std::vector<double>& sup,
                                      std::vector<double> rhs) {
  const std::size_t n = diag.size();
  std::vector<double> c(n, 0.0);
  double denom = diag[0];
  c[0] = n > 1 ? sup[0] / denom : 0.0;
  rhs[0] /= denom;
  for (std::size_t i = 1; i < n; ++i) {
    denom = diag[i] - sub[i] * c[i - 1];
    if (i + 1 < n) c[i] = sup[i] / denom;
    rhs[i] = (rhs[i] - sub[i] * rhs[i - 1]) / denom;
  }
  for (std::size_t i = n - 1; i-- > 0;) rhs[i] -= c[i] * rhs[i + 1];
  return rhs;
}

// Cyclic tridiagonal (corners: row 0 col n-1 = sub[0], row n-1 col 0 =
// sup[n-1]) by Sherman–Morrison; n >= 3.
std::vector<double> solve_cyclic(const std::vector<double>& sub, std::vector<double> diag,
                                 const std::vector<double>& sup, std::vector<double> rhs) {
  const std::size_t n = diag.size();
  const double beta = sub[0], alpha = sup[n - 1];
  const double gamma = -diag[0];
  diag[0] -= gamma;
  diag[n - 1] -= alpha * beta / gamma;
  const std::vector<double> x = solve_tridiagonal(sub, diag, sup, std::move(rhs));
  std::vector<double> u(n, 0.0);
  u[0] = gamma;
  u[n - 1] = alpha;
  const std::vector<double> z = solve_tridiagonal(sub, diag, sup, u);
  const double fact =
      (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = x[i] - fact * z[i];
  return out;
}

// Second derivatives at the knots.
std::vector<double> moments(const std::vector<double>& h, std::span<const double> y,
                            SplineBoundary bc) {
  const std::size_t n = y.size();
  std::vector<double> delta(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) delta[i] = (y[i + 1] - y[i]) / h[i];
  std::vector<double> M(n, 0.0);
  if (bc == SplineBoundary::kNatural) {
    if (n < 3) return M;
    const std::size_t m = n - 2;  // unknowns M[1..n-2]
    std::vector<double> sub(m), diag(m), sup(m), rhs(m);
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = k + 1;
      sub[k] = h[i - 1];
      diag[k] = 2.0 * (h[i - 1] + h[i]);
      sup[k] = h[i];
      rhs[k] = 6.0 * (delta[i] - delta[i - 1]);
    }
    const std::vector<double> inner = solve_tridiagonal(sub, diag, sup, rhs);
    std::copy(inner.begin(), inner.end(), M.begin() + 1);
    return M;
  }
  const std::size_t m = n - 1;  // unknowns M[0..n-2], M[n-1] = M[0]
  if (m < 2) return M;          // two knots, equal values: a constant
  std::vector<double> sub(m), diag(m), sup(m), rhs(m);
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t prev = (i + m - 1) % m;
    sub[i] = h[prev];
    diag[i] = 2.0 * (h[prev] + h[i]);
    sup[i] = h[i];
    rhs[i] = 6.0 * (delta[i] - delta[prev]);
  }
  std::vector<double> sol;
  if (m == 2) {  // both neighbours are the same unknown: a dense 2×2
    const double a00 = diag[0], a01 = sub[0] + sup[0];
    const double a10 = sub[1] + sup[1], a11 = diag[1];
    const double det = a00 * a11 - a01 * a10;
    sol = {(rhs[0] * a11 - a01 * rhs[1]) / det, (a00 * rhs[1] - a10 * rhs[0]) / det};
  } else {
    sol = solve_cyclic(sub, diag, sup, rhs);
  }
  std::copy(sol.begin(), sol.end(), M.begin());
  M[n - 1] = M[0];
  return M;
}

}  // namespace

CubicSpline::CubicSpline(std::span<const double> x, std::span<const double> y,
                         SplineBoundary bc)
    : x_(x.begin(), x.end()), bc_(bc) {
  const std::size_t n = x.size();
  if (n != y.size()) throw std::invalid_argument("CubicSpline: x and y differ in size");
  if (n < 2) throw std::invalid_argument("CubicSpline: needs at least 2 knots");
  std::vector<double> h(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    if (!(h[i] > 0.0)) throw std::invalid_argument("CubicSpline: x must increase strictly");
  }
  std::vector<double> yy(y.begin(), y.end());
  if (bc == SplineBoundary::kPeriodic) {
    const double scale = std::max({1.0, std::abs(y.front()), std::abs(y.back())});
    if (std::abs(y.front() - y.back()) > 1e-9 * scale)
      throw std::invalid_argument("CubicSpline: periodic needs y.front() == y.back()");
    yy.back() = yy.front();
  }
  const std::vector<double> M = moments(h, yy, bc);
  coef_.resize(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    coef_[i] = {yy[i], (yy[i + 1] - yy[i]) / h[i] - h[i] * (2.0 * M[i] + M[i + 1]) / 6.0,
                M[i] / 2.0, (M[i + 1] - M[i]) / (6.0 * h[i])};
  }
}

std::size_t CubicSpline::segment(double x, double& shift) const noexcept {
  shift = 0.0;
  if (bc_ == SplineBoundary::kPeriodic) {
    const double period = x_.back() - x_.front();
    const double wrapped = x - period * std::floor((x - x_.front()) / period);
    shift = x - wrapped;
    x = wrapped;
  }
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  const std::size_t idx = it == x_.begin() ? 0 : static_cast<std::size_t>(it - x_.begin()) - 1;
  return std::min(idx, coef_.size() - 1);
}

double CubicSpline::derivative(double x) const noexcept {
  if (coef_.empty()) return 0.0;
  double shift = 0.0;
  const std::size_t i = segment(x, shift);
  const std::array<double, 4>& c = coef_[i];
  const double dx = x - shift - x_[i];
  return c[1] + dx * (2.0 * c[2] + dx * 3.0 * c[3]);
}

}  // namespace knoblab::model
