#include "position_cells.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace knoblab::fit::detail {

const CellInterpolant& CellInterpolant::get() {
  static const CellInterpolant ip = [] {
    constexpr int n = kCellDegree + 1;
    CellInterpolant out;
    Eigen::Matrix<double, n, n> vandermonde;
    for (int j = 0; j < n; ++j) {
      const double x = std::cos(std::numbers::pi * (2 * j + 1) / (2 * n));
      out.nodes[static_cast<std::size_t>(j)] = x;
      for (int k = 0; k < n; ++k) vandermonde(j, k) = std::pow(x, k);
    }
    const Eigen::Matrix<double, n, n> inv = vandermonde.inverse();
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < n; ++j) {
        out.to_monomial[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)] = inv(k, j);
      }
    }
    return out;
  }();
  return ip;
}

namespace {

int group_of(double omega) { return omega > 0 ? 1 : omega < 0 ? -1 : 0; }

// Adds sign·zzᵀ to packed upper-triangle sums.
void add_outer(std::array<double, kCellPacked>& s, const std::array<double, kCellCols>& z,
               double sign) {
  std::size_t k = 0;
#pragma GCC unroll 8
  for (std::size_t a = 0; a < kCellCols; ++a) {
    const double za = sign * z[a];
#pragma GCC unroll 8
    for (std::size_t b = a; b < kCellCols; ++b) s[k++] += za * z[b];
  }
}

// Adds Σ zzᵀ over rows[begin, end), all in one cell, to that cell's sums.
// The sums are local while the run lasts: summing into the cell in memory
// would chain every add of every row through a store and a load.
void add_run(const CellRows& v, std::span<const std::uint32_t> rows, Cell& cell) {
  std::array<double, kCellPacked> s{};
  for (std::uint32_t i : rows) add_outer(s, v.z(i), 1.0);
  for (std::size_t k = 0; k < kCellPacked; ++k) cell.sums[k] += s[k];
  cell.count += static_cast<std::uint32_t>(rows.size());
}

// The smallest and largest position over the rows (two independent pairs of
// running extremes, so the compares do not wait on one another).
std::array<double, 2> position_range(const FitData& d, std::span<const std::uint32_t> rows) {
  std::array<double, 4> m{d.theta[rows[0]], d.theta[rows[0]], d.theta[rows[0]], d.theta[rows[0]]};
  std::size_t j = 0;
  for (; j + 1 < rows.size(); j += 2) {
    const double a = d.theta[rows[j]], b = d.theta[rows[j + 1]];
    m[0] = std::min(m[0], a), m[1] = std::max(m[1], a);
    m[2] = std::min(m[2], b), m[3] = std::max(m[3], b);
  }
  if (j < rows.size()) m[0] = std::min(m[0], d.theta[rows[j]]), m[1] = std::max(m[1], d.theta[rows[j]]);
  return {std::min(m[0], m[2]), std::max(m[1], m[3])};
}

}  // namespace

PositionCells::PositionCells(const FitData& d, std::span<const std::uint32_t> rows,
                             double max_width)
    : d_(&d), cell_of_(d.size(), kNone), removed_(d.size(), false) {
  const auto [lo, hi] = position_range(d, rows);
  const double range = std::max(hi - lo, 1e-12);
  bins_ = max_width > 0 ? static_cast<std::size_t>(std::ceil(range / max_width)) : 1;
  bins_ = std::clamp<std::size_t>(bins_, 1, 1u << 20);
  half_ = range / static_cast<double>(bins_) / 2;
  inv_half_ = 1.0 / half_;
  lo_ = lo;
  cells_.resize(bins_ * 3);
  centers_.resize(bins_ * 3);
  for (std::size_t b = 0; b < bins_; ++b) {
    for (int g = 0; g < 3; ++g) {
      Cell& c = cells_[b * 3 + static_cast<std::size_t>(g)];
      c.center = lo_ + (2 * static_cast<double>(b) + 1) * half_;
      c.group = g - 1;
      centers_[b * 3 + static_cast<std::size_t>(g)] = c.center;
    }
  }
  // Each row's cell first, then the sums run by run.
  const double bins_per_rad = 1.0 / (2 * half_);
  for (std::uint32_t i : rows) {
    const auto b = std::min(static_cast<std::size_t>((d.theta[i] - lo_) * bins_per_rad), bins_ - 1);
    cell_of_[i] = static_cast<std::uint32_t>(b * 3 + static_cast<std::size_t>(group_of(d.omega[i]) + 1));
  }
  const CellRows view = this->rows();
  for (std::size_t j = 0; j < rows.size();) {
    const std::uint32_t c = cell_of_[rows[j]];
    std::size_t end = j + 1;
    while (end < rows.size() && cell_of_[rows[end]] == c) ++end;
    add_run(view, rows.subspan(j, end - j), cells_[c]);
    j = end;
  }
}

void PositionCells::remove(std::uint32_t row) {
  const std::uint32_t c = cell_of_[row];
  if (c == kNone || removed_[row]) return;
  add_outer(cells_[c].sums, z(row), -1.0);
  --cells_[c].count;
  removed_[row] = true;
}

void PositionCells::factor() {
  for (Cell& c : cells_) {
    std::size_t k = 0;
    for (int a = 0; a < kCellCols; ++a) {
      for (int b = a; b < kCellCols; ++b) c.gram(a, b) = c.gram(b, a) = c.sums[k++];
    }
    if (c.count == 0) {
      c.root.setZero();
      continue;
    }
    const CellMatrix& g = c.gram;
    // G = Pᵀ·L·D·Lᵀ·P; R = D^½·Lᵀ·P (D clamped at 0 against round-off:
    // a cell with fewer than 8 samples is singular).
    const Eigen::LDLT<CellMatrix> ldlt(g);
    const Eigen::Matrix<double, kCellCols, 1> root_d = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt();
    const CellMatrix P = ldlt.transpositionsP() * CellMatrix::Identity();
    const CellMatrix lt = ldlt.matrixU();
    c.root = root_d.asDiagonal() * lt * P;
  }
}

namespace {

template <int N>
CellModel cell_model_n(ModelKind kind, const PositionCells& cells, const double* p,
                       bool derivatives) {
  using Jet = ceres::Jet<double, N>;
  std::array<Jet, N> pj;
  for (int k = 0; k < N; ++k) pj[static_cast<std::size_t>(k)] = Jet(p[k], k);
  const std::size_t nc = cells.cells().size();
  CellModel out;
  out.rows = cells.rows();
  out.n = derivatives ? N : 0;
  out.v.resize(nc * kCellCols);
  out.dv.resize(nc * kCellCols * out.n);
  out.friction.resize(nc * 2);
  for (std::size_t c = 0; c < nc; ++c) {
    Jet vj[kCellCols], fj[2];
    cell_vector(kind, pj.data(), cells.cells()[c], cells.half_width(), vj, fj);
    for (std::size_t a = 0; a < kCellCols; ++a) {
      out.v[c * kCellCols + a] = vj[a].a;
      for (std::size_t k = 0; k < out.n; ++k) out.dv[(c * kCellCols + a) * out.n + k] = vj[a].v[k];
    }
    out.friction[2 * c] = fj[0].a, out.friction[2 * c + 1] = fj[1].a;
  }
  return out;
}

}  // namespace

CellModel cell_model(ModelKind kind, const PositionCells& cells, const double* p,
                     bool derivatives) {
  return kind == ModelKind::Thesis6 ? cell_model_n<kThesisParams>(kind, cells, p, derivatives)
                                    : cell_model_n<kRenderParams>(kind, cells, p, derivatives);
}

void evaluate_cells(ModelKind kind, const PositionCells& cells, std::span<const std::uint32_t> rows,
                    const double* p, std::span<double> residuals, std::span<double> jacobian) {
  const CellModel m = cell_model(kind, cells, p, !jacobian.empty());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::uint32_t i = rows[j];
    residuals[j] = m.residual(i);
    if (!jacobian.empty()) {
      const std::array<double, kCellCols> z = m.rows.z(i);
      const double* dc = m.dv.data() + std::size_t{cells.cell_of(i)} * kCellCols * m.n;
      double* J = jacobian.data() + j * m.n;
      for (std::size_t k = 0; k < m.n; ++k) J[k] = 0.0;
      for (std::size_t a = 1; a < kCellCols; ++a) {  // z₀ = τ meets v₀ = −1: no derivative
        for (std::size_t k = 0; k < m.n; ++k) J[k] += z[a] * dc[a * m.n + k];
      }
    }
  }
}

}  // namespace knoblab::fit::detail
