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

#include "knoblab/fit/covariance.hpp"
#include "knoblab/fit/stats.hpp"
#include "position_cells.hpp"
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

namespace {

// The sandwich from its parts over the free parameters: JᵀJ (nf × nf), the
// batch sums of the scores (nf × B), the residual sum of squares and the
// row count.
CovarianceEstimate sandwich(const Eigen::MatrixXd& jtj, const Eigen::MatrixXd& batch_sums,
                            double rss, std::size_t m, const std::vector<Eigen::Index>& free,
                            std::size_t n) {
  CovarianceEstimate out;
  out.rss = rss;
  const auto nf = static_cast<Eigen::Index>(free.size());
  const Eigen::MatrixXd bread = jtj.ldlt().solve(Eigen::MatrixXd::Identity(nf, nf));
  const double B = static_cast<double>(kBatches);
  const Eigen::MatrixXd meat = batch_sums * batch_sums.transpose() * (B / (B - 1));
  const Eigen::MatrixXd cov = bread * meat * bread;
  const double dof = static_cast<double>(m) - static_cast<double>(nf);
  const double sigma2 = dof > 0 ? rss / dof : 0.0;

  out.covariance.assign(n * n, 0.0);
  out.se.assign(n, 0.0);
  double inflation = 0.0;
  for (Eigen::Index a = 0; a < nf; ++a) {
    const auto k = static_cast<std::size_t>(free[static_cast<std::size_t>(a)]);
    for (Eigen::Index c = 0; c < nf; ++c) {
      out.covariance[k * n + static_cast<std::size_t>(free[static_cast<std::size_t>(c)])] = cov(a, c);
    }
    out.se[k] = std::sqrt(std::max(0.0, cov(a, a)));
    const double classic = sigma2 * bread(a, a);
    inflation += classic > 0 ? cov(a, a) / classic : 1.0;
  }
  out.inflation = nf > 0 ? inflation / static_cast<double>(nf) : 1.0;
  out.t95 = student_t_quantile(0.975, B - 1);
  return out;
}

std::vector<Eigen::Index> free_parameters(const std::vector<bool>& fitted) {
  std::vector<Eigen::Index> free;
  for (std::size_t k = 0; k < fitted.size(); ++k) {
    if (fitted[k]) free.push_back(static_cast<Eigen::Index>(k));
  }
  return free;
}

// The batch a row belongs to: B contiguous, equal shares of the rows; and
// the first row of batch b.
std::size_t batch_of(std::size_t j, std::size_t m) { return j * kBatches / m; }
std::size_t batch_begin(std::size_t b, std::size_t m) { return (b * m + kBatches - 1) / kBatches; }

}  // namespace

CovarianceEstimate covariance_from_cells(ModelKind kind, const PositionCells& cells,
                                         std::span<const std::uint32_t> rows, const double* p,
                                         const std::vector<bool>& fitted,
                                         std::span<const double> residuals) {
  const bool given = residuals.size() == rows.size();
  const CellModel cm = cell_model(kind, cells, p, true);
  const std::size_t n = cm.n, m = rows.size();
  const std::vector<Eigen::Index> free = free_parameters(fitted);
  const auto nf = static_cast<Eigen::Index>(free.size());
  using RowMajor = Eigen::Matrix<double, kCellCols, Eigen::Dynamic, Eigen::RowMajor>;
  // Each cell's ∂v/∂p over the free parameters (8 × nf): a row's Jacobian is zᵀ·dv.
  const std::size_t nc = cells.cells().size();
  std::vector<double> dvf(nc * kCellCols * free.size());
  for (std::size_t c = 0; c < nc; ++c) {
    const Eigen::Map<const RowMajor> dv(cm.dv.data() + c * kCellCols * n, kCellCols,
                                        static_cast<Eigen::Index>(n));
    Eigen::Map<RowMajor>(dvf.data() + c * kCellCols * free.size(), kCellCols, nf) = dv(Eigen::all, free);
  }
  auto dv_free = [&](std::size_t c) {
    return Eigen::Map<const RowMajor>(dvf.data() + c * kCellCols * free.size(), kCellCols, nf);
  };

  // Bread: JᵀJ = Σ_cells dvᵀ·G·dv, G the cell's Gram matrix of the rows it holds.
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(nf, nf);
  for (std::size_t c = 0; c < nc; ++c) {
    const Cell& cell = cells.cells()[c];
    if (cell.count == 0) continue;
    const CellMatrix g = cell.gram.selfadjointView<Eigen::Upper>();
    jtj.noalias() += dv_free(c).transpose() * g * dv_free(c);
  }

  // Meat: the batch sums of the scores J_iᵀ·r_i = dvᵀ·(z_i·r_i), with z·r
  // summed locally while the rows stay in one cell.
  Eigen::MatrixXd batch_sums = Eigen::MatrixXd::Zero(nf, static_cast<Eigen::Index>(kBatches));
  double rss = 0.0;
  for (std::size_t b = 0; b < kBatches; ++b) {
    std::array<double, kCellCols> w{};
    std::uint32_t run_cell = PositionCells::kNone;
    auto flush = [&] {
      if (run_cell == PositionCells::kNone) return;
      const Eigen::Map<const Eigen::Matrix<double, kCellCols, 1>> wv(w.data());
      batch_sums.col(static_cast<Eigen::Index>(b)).noalias() += dv_free(run_cell).transpose() * wv;
      w = {};
    };
    for (std::size_t j = batch_begin(b, m); j < batch_begin(b + 1, m); ++j) {
      const std::uint32_t i = rows[j];
      const std::uint32_t c = cm.rows.cell_of[i];
      if (c != run_cell) flush(), run_cell = c;
      const std::array<double, kCellCols> z = cm.rows.z(i);
      const double r = given ? residuals[j] : cm.residual(i);
#pragma GCC unroll 8
      for (std::size_t a = 0; a < kCellCols; ++a) w[a] += z[a] * r;
      rss += r * r;
    }
    flush();
  }
  CovarianceEstimate out = sandwich(jtj, batch_sums, rss, m, free, n);

  // The fitted curve's standard deviation at row i is √(zᵀ·Q·z) with
  // Q = dv·C·dvᵀ per cell (C the covariance): 8 × 8 per cell, not n per row.
  const Eigen::Map<const Eigen::MatrixXd> C(out.covariance.data(), static_cast<Eigen::Index>(n),
                                            static_cast<Eigen::Index>(n));
  std::vector<CellMatrix> q(nc);
  for (std::size_t c = 0; c < q.size(); ++c) {
    if (cells.cells()[c].count == 0) continue;
    const Eigen::Map<const RowMajor> dv(cm.dv.data() + c * kCellCols * n, kCellCols,
                                        static_cast<Eigen::Index>(n));
    q[c] = dv * C * dv.transpose();
  }
  double sd = 0.0;
  const std::size_t stride = summary_stride(m);
  std::size_t used = 0;
  for (std::size_t j = 0; j < m; j += stride, ++used) {
    const std::uint32_t i = rows[j];
    const CellMatrix& qc = q[cm.rows.cell_of[i]];
    const std::array<double, kCellCols> z = cm.rows.z(i);
    double v = 0.0;
#pragma GCC unroll 8
    for (int a = 1; a < kCellCols; ++a) {  // z₀ = τ carries no derivative
      double s = 0.5 * qc(a, a) * z[static_cast<std::size_t>(a)];
#pragma GCC unroll 8
      for (int b = a + 1; b < kCellCols; ++b) s += qc(a, b) * z[static_cast<std::size_t>(b)];
      v += 2 * s * z[static_cast<std::size_t>(a)];
    }
    sd += std::sqrt(std::max(0.0, v));
  }
  out.curve_sd_mean = used > 0 ? sd / static_cast<double>(used) : 0.0;
  return out;
}

}  // namespace knoblab::fit::detail

namespace knoblab::fit {

using detail::batch_of;
using detail::kBatches;
using detail::free_parameters;
using detail::sandwich;
using detail::summary_stride;

CovarianceEstimate covariance_from_rows(std::vector<double> residuals,
                                        std::vector<double> jacobian, std::size_t n,
                                        const std::vector<bool>& fitted) {
  const std::size_t m = residuals.size();
  const std::vector<Eigen::Index> free = free_parameters(fitted);
  const auto nf = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(nf, nf);
  Eigen::MatrixXd batch_sums = Eigen::MatrixXd::Zero(nf, static_cast<Eigen::Index>(kBatches));
  Eigen::VectorXd g(nf);
  double rss = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const double* J = jacobian.data() + i * n;
    for (Eigen::Index a = 0; a < nf; ++a) g(a) = J[free[static_cast<std::size_t>(a)]];
    jtj.selfadjointView<Eigen::Lower>().rankUpdate(g);
    batch_sums.col(static_cast<Eigen::Index>(batch_of(i, m))) += g * residuals[i];
    rss += residuals[i] * residuals[i];
  }
  jtj = jtj.selfadjointView<Eigen::Lower>();
  CovarianceEstimate out = sandwich(jtj, batch_sums, rss, m, free, n);
  double sd = 0.0;
  const std::size_t stride = summary_stride(m);
  std::size_t used = 0;
  for (std::size_t i = 0; i < m; i += stride, ++used) {
    const double* J = jacobian.data() + i * n;
    double v = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      for (std::size_t q = 0; q < n; ++q) v += J[p] * out.covariance[p * n + q] * J[q];
    }
    sd += std::sqrt(std::max(0.0, v));
  }
  out.curve_sd_mean = used > 0 ? sd / static_cast<double>(used) : 0.0;
  return out;
}

}  // namespace knoblab::fit
