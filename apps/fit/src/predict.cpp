#include <cmath>
#include <numeric>

#include "residual.hpp"

namespace knoblab::fit {

Prediction predict(const FitResult& r, const FitData& d) {
  const std::size_t n = r.params.size(), m = d.size();
  if (n == 0 || r.covariance.size() != n * n) {
    throw std::invalid_argument("predict: the fit result has no parameters or covariance");
  }
  std::vector<std::uint32_t> rows(m);
  std::iota(rows.begin(), rows.end(), 0u);
  std::vector<double> residuals(m), jac(m * n);
  detail::evaluate_rows(r.model, d, rows, r.params.data(), residuals, jac);

  const model::ThesisModel<double> model = thesis_model(r);
  const double s2 = r.residual_sd * r.residual_sd;
  Prediction p;
  p.tau.resize(m), p.acc.resize(m), p.vel.resize(m), p.pos.resize(m);
  p.curve_half.resize(m), p.observation_half.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    const auto parts = model.parts(d.kinematics(i));
    p.acc[i] = parts.acc, p.vel[i] = parts.vel, p.pos[i] = parts.pos;
    p.tau[i] = parts.total();
    const double* J = jac.data() + i * n;
    double v = 0.0;
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = 0; b < n; ++b) v += J[a] * r.covariance[a * n + b] * J[b];
    }
    v = std::max(0.0, v);
    p.curve_half[i] = r.t95 * std::sqrt(v);
    p.observation_half[i] = r.t95 * std::sqrt(v + s2);
  }
  return p;
}

}  // namespace knoblab::fit
