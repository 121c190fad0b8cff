// Parameter covariance: the sandwich estimate with batch means of the scores.
//
// Residuals of captured data are correlated (filtered, and every model
// misses something), and then σ²(JᵀJ)⁻¹ is too small. With scores
// g_i = J_iᵀ r_i summed over B contiguous batches, S_b = Σ_{i∈b} g_i,
//   Cov(p̂) ≈ (JᵀJ)⁻¹ · [B/(B−1) Σ_b S_b S_bᵀ] · (JᵀJ)⁻¹,
// which holds while the batches are longer than the residuals' correlation.
// Σ_b S_b = 0 at a least-squares optimum, hence B − 1 degrees of freedom.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "knoblab/fit/stats.hpp"
#include "residual.hpp"

namespace knoblab::fit::detail {

namespace {
constexpr std::size_t kBatches = 64;
}

void evaluate_rows(ModelKind kind, const FitData& data, std::span<const std::uint32_t> rows,
                   const double* p, std::span<double> residuals, std::span<double> jacobian) {
  const std::size_t n = static_cast<std::size_t>(param_count(kind));
  for (std::size_t start = 0; start < rows.size(); start += kChunk) {
    const std::size_t len = std::min(kChunk, rows.size() - start);
    const auto cost = make_chunk_cost(kind, data, rows.subspan(start, len));
    const double* params[] = {p};
    double* jac[] = {jacobian.empty() ? nullptr : jacobian.data() + start * n};
    cost->Evaluate(params, residuals.data() + start, jacobian.empty() ? nullptr : jac);
  }
}

CovarianceEstimate estimate_covariance(ModelKind kind, const FitData& data,
                                       std::span<const std::uint32_t> rows, const double* p,
                                       const std::vector<bool>& fitted) {
  const std::size_t n = static_cast<std::size_t>(param_count(kind));
  std::vector<double> residuals(rows.size()), jacobian(rows.size() * n);
  evaluate_rows(kind, data, rows, p, residuals, jacobian);
  return covariance_from_rows(std::move(residuals), std::move(jacobian), n, fitted);
}

CovarianceEstimate covariance_from_rows(std::vector<double> residuals,
                                        std::vector<double> jacobian, std::size_t n,
                                        const std::vector<bool>& fitted) {
  const std::size_t m = residuals.size();
  CovarianceEstimate out;
  out.residuals = std::move(residuals);
  out.jacobian = std::move(jacobian);

  std::vector<Eigen::Index> free;
  for (std::size_t k = 0; k < n; ++k) {
    if (fitted[k]) free.push_back(static_cast<Eigen::Index>(k));
  }
  const auto nf = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(nf, nf);
  Eigen::MatrixXd batch_sums = Eigen::MatrixXd::Zero(nf, static_cast<Eigen::Index>(kBatches));
  Eigen::VectorXd g(nf);
  for (std::size_t i = 0; i < m; ++i) {
    const double* J = out.jacobian.data() + i * n;
    for (Eigen::Index a = 0; a < nf; ++a) g(a) = J[free[static_cast<std::size_t>(a)]];
    jtj.selfadjointView<Eigen::Lower>().rankUpdate(g);
    const auto b = static_cast<Eigen::Index>(i * kBatches / m);
    batch_sums.col(b) += g * out.residuals[i];
    out.rss += out.residuals[i] * out.residuals[i];
  }
  jtj = jtj.selfadjointView<Eigen::Lower>();
  const Eigen::MatrixXd bread = jtj.ldlt().solve(Eigen::MatrixXd::Identity(nf, nf));
  const double B = static_cast<double>(kBatches);
  const Eigen::MatrixXd meat = batch_sums * batch_sums.transpose() * (B / (B - 1));
  const Eigen::MatrixXd sandwich = bread * meat * bread;
  const double dof = static_cast<double>(m) - static_cast<double>(nf);
  const double sigma2 = dof > 0 ? out.rss / dof : 0.0;

  out.covariance.assign(n * n, 0.0);
  out.se.assign(n, 0.0);
  double inflation = 0.0;
  for (Eigen::Index a = 0; a < nf; ++a) {
    for (Eigen::Index c = 0; c < nf; ++c) {
      out.covariance[static_cast<std::size_t>(free[static_cast<std::size_t>(a)]) * n +
                     static_cast<std::size_t>(free[static_cast<std::size_t>(c)])] = sandwich(a, c);
    }
    const std::size_t k = static_cast<std::size_t>(free[static_cast<std::size_t>(a)]);
    out.se[k] = std::sqrt(std::max(0.0, sandwich(a, a)));
    const double classic = sigma2 * bread(a, a);
    inflation += classic > 0 ? sandwich(a, a) / classic : 1.0;
  }
  out.inflation = nf > 0 ? inflation / static_cast<double>(nf) : 1.0;
  out.t95 = student_t_quantile(0.975, B - 1);
  return out;
}

}  // namespace knoblab::fit::detail
