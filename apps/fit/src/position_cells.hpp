// The knob model's least-squares problem compressed into position cells, so
// Ceres iterates over a few hundred cells instead of 10⁵ samples. Internal to
// knoblab_fit.
//
// Why this is exact (up to interpolation): within one direction of motion
// (ω < 0, ω = 0, ω > 0) Eq. 6 and Eq. 14 are affine in α and ω,
//   τ̂ = M·α + B_g·ω + c_g + D(θ),
// and only the detent term D = A·sin(θ/P + S) depends on position. Over a
// cell — a position bin about P/4 wide (fit_knob rebuilds the cells should P
// shrink by a tenth), one direction — D is replaced by its quartic
// interpolant through five Chebyshev nodes, D ≈ Σ d_k·u^k with u the position
// within the bin scaled to [−1, 1] (error < 2·(1/16)⁵/5!·A ≈ 2e-8·A at P/4,
// 3e-8·A at P/3.6).
// Then each sample's residual is z·v with z = (τ, α, ω, u⁰ … u⁴) the data and
// v = (−1, M, B_g, c_g + d₀, d₁ … d₄) the model, so a cell's residual norm is
// vᵀ·G·v with G = Σ zzᵀ, and the cell contributes the 8 residuals R·v,
// RᵀR = G. M, B_g, c_g and D(nodes) come from the model core's terms
// (Inertia, CoulombViscous — affine within a direction, so two evaluations
// give slope and intercept — and Detents), so autodiff flows through them.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/model/models.hpp"
#include "residual.hpp"

namespace knoblab::fit::detail {

inline constexpr int kCellCols = 8;  // τ, α, ω, u⁰ … u⁴
inline constexpr int kCellDegree = 4;
using CellMatrix = Eigen::Matrix<double, kCellCols, kCellCols>;

// Chebyshev nodes of the interpolant on [−1, 1] and the map from the detent
// torque at the nodes to the monomial coefficients d₀ … d₄.
struct CellInterpolant {
  std::array<double, kCellDegree + 1> nodes{};
  std::array<std::array<double, kCellDegree + 1>, kCellDegree + 1> to_monomial{};
  static const CellInterpolant& get();
};

inline constexpr int kCellPacked = kCellCols * (kCellCols + 1) / 2;

struct Cell {
  double center = 0.0;  // rad
  int group = 0;        // sign of ω: −1, 0, +1
  std::uint32_t count = 0;
  std::array<double, kCellPacked> sums{};  // Σ zzᵀ, upper triangle row by row
  CellMatrix gram = CellMatrix::Zero();  // the same as a full matrix (factor())
  CellMatrix root = CellMatrix::Zero();  // R with RᵀR = gram (factor())
};

// Flat pointers to what a row's data vector needs, for tight loops over rows
// (a copy in the loop re-reads nothing through the containers).
struct CellRows {
  const double *theta = nullptr, *omega = nullptr, *alpha = nullptr, *torque = nullptr;
  const std::uint32_t* cell_of = nullptr;
  const double* center = nullptr;  // per cell
  double inv_half = 0.0;

  // Row i's position within its cell, scaled to [−1, 1].
  double u(std::uint32_t i) const { return (theta[i] - center[cell_of[i]]) * inv_half; }
  // Row i's data vector z = (τ, α, ω, u⁰ … u⁴).
  std::array<double, kCellCols> z(std::uint32_t i) const {
    const double x = u(i), x2 = x * x;
    return {torque[i], alpha[i], omega[i], 1.0, x, x2, x2 * x, x2 * x2};
  }
};

class PositionCells {
 public:
  // Cells of width ≤ max_width over the rows' positions (one bin when
  // max_width is 0: no detent term).
  PositionCells(const FitData& d, std::span<const std::uint32_t> rows, double max_width);

  // Removes one sample (a stuck one, an outlier) from its cell; it keeps its
  // cell assignment, so it can still be evaluated.
  void remove(std::uint32_t row);
  bool removed(std::uint32_t row) const { return removed_[row]; }
  // Computes every cell's gram and R; call after the last remove().
  void factor();

  const std::vector<Cell>& cells() const { return cells_; }
  double half_width() const { return half_; }
  // The cell and position within it (u in [−1, 1]) of row i; cell_of is
  // kNone for a row that was never added.
  static constexpr std::uint32_t kNone = 0xffffffffu;
  std::uint32_t cell_of(std::uint32_t i) const { return cell_of_[i]; }
  CellRows rows() const {
    return {d_->theta.data(), d_->omega.data(), d_->alpha.data(), d_->torque.data(),
            cell_of_.data(), centers_.data(), inv_half_};
  }
  std::array<double, kCellCols> z(std::uint32_t i) const { return rows().z(i); }

 private:
  const FitData* d_;
  double lo_ = 0.0, half_ = 0.0, inv_half_ = 0.0;
  std::size_t bins_ = 1;
  std::vector<Cell> cells_;                // bins_ × 3 groups, empty ones kept
  std::vector<double> centers_;            // per cell, apart from the bulky Cell
  std::vector<std::uint32_t> cell_of_;     // per row of d
  std::vector<bool> removed_;              // per row of d
};

// The model vector v of one cell at parameters p (any scalar type, so
// autodiff can run through it).
// `friction`, when given, receives the direction's slope and intercept
// (B_g, c_g): the velocity part of a sample is B_g·ω + c_g.
template <typename T>
void cell_vector(ModelKind kind, const T* p, const Cell& c, double half, T* v,
                 T* friction = nullptr) {
  const model::ThesisModel<T> m = as_thesis(kind, p);
  v[0] = T(-1);
  v[1] = m.inertia.torque(T(1));
  T intercept(0);
  if (c.group == 0) {
    v[2] = T(0);
  } else {
    const double s = c.group;  // friction is affine in ω within a direction
    const T f1 = m.friction.torque(T(s)), f2 = m.friction.torque(T(2 * s));
    v[2] = (f2 - f1) / T(s);
    intercept = T(2) * f1 - f2;
  }
  const CellInterpolant& ip = CellInterpolant::get();
  T at_node[kCellDegree + 1];
  for (int j = 0; j <= kCellDegree; ++j) {
    at_node[j] = m.detents.torque(T(c.center + half * ip.nodes[static_cast<std::size_t>(j)]));
  }
  for (int k = 0; k <= kCellDegree; ++k) {
    T dk(0);
    for (int j = 0; j <= kCellDegree; ++j) {
      dk += ip.to_monomial[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)] * at_node[j];
    }
    v[3 + k] = dk;
  }
  v[3] += intercept;
  if (friction) friction[0] = v[2], friction[1] = intercept;
}

// Every cell's model vector at one parameter vector p, for evaluating single
// rows: v (cells × 8), when asked ∂v/∂p (cells × 8 × n, row-major per cell),
// and each cell's friction slope and intercept (B_g, c_g).
struct CellModel {
  CellRows rows;
  std::size_t n = 0;  // parameters; 0: no derivatives
  std::vector<double> v, dv, friction;

  // Row i's residual (model − measured) and velocity part B_g·ω + c_g.
  double residual(std::uint32_t i) const {
    const double* vc = v.data() + std::size_t{rows.cell_of[i]} * kCellCols;
    const double u = rows.u(i);  // z·v with the u powers by Horner
    return vc[0] * rows.torque[i] + vc[1] * rows.alpha[i] + vc[2] * rows.omega[i] +
           (vc[3] + u * (vc[4] + u * (vc[5] + u * (vc[6] + u * vc[7]))));
  }
  double velocity_part(std::uint32_t i) const {
    const double* f = friction.data() + 2 * std::size_t{rows.cell_of[i]};
    return f[0] * rows.omega[i] + f[1];
  }
};
CellModel cell_model(ModelKind kind, const PositionCells& cells, const double* p,
                     bool derivatives);

// Residuals (model − measured) and, when `jacobian` is not empty, Jacobian
// rows (rows.size() × n) of the given rows at p, through the cells.
void evaluate_cells(ModelKind kind, const PositionCells& cells, std::span<const std::uint32_t> rows,
                    const double* p, std::span<double> residuals, std::span<double> jacobian);

// The covariance (covariance.cpp) through the cells: JᵀJ from the cells'
// Gram matrices, the scores and the curve's band in one pass each over rows.
// `residuals` (model − measured of rows at p), when the caller has them,
// spares recomputing them.
CovarianceEstimate covariance_from_cells(ModelKind kind, const PositionCells& cells,
                                         std::span<const std::uint32_t> rows, const double* p,
                                         const std::vector<bool>& fitted,
                                         std::span<const double> residuals = {});

struct CellResidual {
  ModelKind kind;
  const Cell* cell;
  double half;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    T v[kCellCols];
    cell_vector(kind, p, *cell, half, v);
    for (int a = 0; a < kCellCols; ++a) {
      T s(0);
      for (int b = 0; b < kCellCols; ++b) s += cell->root(a, b) * v[b];
      r[a] = s;
    }
    return true;
  }
};

}  // namespace knoblab::fit::detail
