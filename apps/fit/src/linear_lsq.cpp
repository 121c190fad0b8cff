#include "knoblab/fit/linear_lsq.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/stats.hpp"

namespace knoblab::fit {

template <std::size_t N>
typename LinearLsq<N>::Solution LinearLsq<N>::solve() const {
  if (n_ <= static_cast<std::int64_t>(N) + 1)
    throw FitDataError("least squares with " + std::to_string(N) + " parameters needs more than " +
                       std::to_string(N + 1) + " samples, got " + std::to_string(n_));
  // Gauss–Jordan with partial pivoting on [XᵀX | I].
  std::array<std::array<double, 2 * N>, N> m{};
  double scale = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = 0; j < N; ++j) m[i][j] = xtx_[i][j];
    m[i][N + i] = 1.0;
    scale = std::max(scale, std::abs(xtx_[i][i]));
  }
  if (!(scale > 0.0) || !std::isfinite(scale)) throw FitDataError("least squares: the data carry no signal");
  for (std::size_t c = 0; c < N; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < N; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    if (std::abs(m[p][c]) <= 1e-12 * scale)
      throw FitDataError("least squares: the design is singular (the data do not determine every parameter)");
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
  s.dof = n_ - static_cast<std::int64_t>(N);
  for (std::size_t i = 0; i < N; ++i) {
    double b = 0.0;
    for (std::size_t j = 0; j < N; ++j) b += m[i][N + j] * xty_[j];
    s.beta[i] = b;
  }
  // RSS = yᵀy − 2βᵀXᵀy + βᵀXᵀXβ = yᵀy − βᵀXᵀy at the optimum.
  double bty = 0.0;
  for (std::size_t i = 0; i < N; ++i) bty += s.beta[i] * xty_[i];
  const double rss = std::max(0.0, yty_ - bty);
  const double sigma2 = rss / static_cast<double>(s.dof);
  s.residual_sd = std::sqrt(sigma2);
  const double t = student_t_quantile(0.975, static_cast<double>(s.dof));
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = 0; j < N; ++j) s.cov[i][j] = sigma2 * m[i][N + j];
    s.se[i] = std::sqrt(std::max(0.0, s.cov[i][i]));
    s.ci95[i] = t * s.se[i];
  }
  return s;
}

template class LinearLsq<1>;
template class LinearLsq<2>;
template class LinearLsq<3>;
template class LinearLsq<4>;

}  // namespace knoblab::fit
