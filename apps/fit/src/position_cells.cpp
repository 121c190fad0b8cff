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

void add_outer(CellMatrix& g, const std::array<double, kCellCols>& z, double sign) {
  for (int a = 0; a < kCellCols; ++a) {
    const double za = sign * z[static_cast<std::size_t>(a)];
    for (int b = a; b < kCellCols; ++b) g(a, b) += za * z[static_cast<std::size_t>(b)];
  }
}

}  // namespace

PositionCells::PositionCells(const FitData& d, std::span<const std::uint32_t> rows,
                             double max_width)
    : d_(&d), cell_of_(d.size(), kNone), removed_(d.size(), false) {
  double lo = d.theta[rows[0]], hi = lo;
  for (std::uint32_t i : rows) lo = std::min(lo, d.theta[i]), hi = std::max(hi, d.theta[i]);
  const double range = std::max(hi - lo, 1e-12);
  bins_ = max_width > 0 ? static_cast<std::size_t>(std::ceil(range / max_width)) : 1;
  bins_ = std::clamp<std::size_t>(bins_, 1, 1u << 20);
  half_ = range / static_cast<double>(bins_) / 2;
  lo_ = lo;
  cells_.resize(bins_ * 3);
  for (std::size_t b = 0; b < bins_; ++b) {
    for (int g = 0; g < 3; ++g) {
      Cell& c = cells_[b * 3 + static_cast<std::size_t>(g)];
      c.center = lo_ + (2 * static_cast<double>(b) + 1) * half_;
      c.group = g - 1;
    }
  }
  for (std::uint32_t i : rows) {
    const auto b = std::min(static_cast<std::size_t>((d.theta[i] - lo_) / (2 * half_)), bins_ - 1);
    const auto c = static_cast<std::uint32_t>(b * 3 + static_cast<std::size_t>(group_of(d.omega[i]) + 1));
    cell_of_[i] = c;
    add_outer(cells_[c].gram, z(i), 1.0);
    ++cells_[c].count;
  }
}

std::array<double, kCellCols> PositionCells::z(std::uint32_t i) const {
  const Cell& c = cells_[cell_of_[i]];
  const double u = (d_->theta[i] - c.center) / half_;
  const double u2 = u * u;
  return {d_->torque[i], d_->alpha[i], d_->omega[i], 1.0, u, u2, u2 * u, u2 * u2};
}

void PositionCells::remove(std::uint32_t row) {
  const std::uint32_t c = cell_of_[row];
  if (c == kNone || removed_[row]) return;
  add_outer(cells_[c].gram, z(row), -1.0);
  --cells_[c].count;
  removed_[row] = true;
}

void PositionCells::factor() {
  for (Cell& c : cells_) {
    if (c.count == 0) continue;
    const CellMatrix g = c.gram.selfadjointView<Eigen::Upper>();
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
void evaluate_cells_n(ModelKind kind, const PositionCells& cells,
                      std::span<const std::uint32_t> rows, const double* p,
                      std::span<double> residuals, std::span<double> jacobian,
                      std::span<double> velocity_part) {
  using Jet = ceres::Jet<double, N>;
  std::array<Jet, N> pj;
  for (int k = 0; k < N; ++k) pj[static_cast<std::size_t>(k)] = Jet(p[k], k);
  // v and ∂v/∂p of every cell, once.
  const std::size_t nc = cells.cells().size();
  std::vector<double> v(nc * kCellCols), dv(nc * kCellCols * N), fr(nc * 2);
  for (std::size_t c = 0; c < nc; ++c) {
    Jet vj[kCellCols], fj[2];
    cell_vector(kind, pj.data(), cells.cells()[c], cells.half_width(), vj, fj);
    for (int a = 0; a < kCellCols; ++a) {
      v[c * kCellCols + static_cast<std::size_t>(a)] = vj[a].a;
      for (int k = 0; k < N; ++k) {
        dv[(c * kCellCols + static_cast<std::size_t>(a)) * N + static_cast<std::size_t>(k)] =
            vj[a].v[k];
      }
    }
    fr[2 * c] = fj[0].a, fr[2 * c + 1] = fj[1].a;
  }
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::uint32_t i = rows[j];
    const std::size_t c = cells.cell_of(i);
    const std::array<double, kCellCols> z = cells.z(i);
    const double* vc = v.data() + c * kCellCols;
    double r = 0.0;
    for (int a = 0; a < kCellCols; ++a) r += z[static_cast<std::size_t>(a)] * vc[a];
    residuals[j] = r;
    if (!jacobian.empty()) {
      double* J = jacobian.data() + j * N;
      const double* dc = dv.data() + c * kCellCols * N;
      for (int k = 0; k < N; ++k) J[k] = 0.0;
      for (int a = 1; a < kCellCols; ++a) {  // z₀ = τ meets v₀ = −1: no derivative
        const double za = z[static_cast<std::size_t>(a)];
        for (int k = 0; k < N; ++k) J[k] += za * dc[a * N + k];
      }
    }
    if (!velocity_part.empty()) velocity_part[j] = fr[2 * c] * z[2] + fr[2 * c + 1];
  }
}

}  // namespace

void evaluate_cells(ModelKind kind, const PositionCells& cells, std::span<const std::uint32_t> rows,
                    const double* p, std::span<double> residuals, std::span<double> jacobian,
                    std::span<double> velocity_part) {
  if (kind == ModelKind::Thesis6) {
    evaluate_cells_n<kThesisParams>(kind, cells, rows, p, residuals, jacobian, velocity_part);
  } else {
    evaluate_cells_n<kRenderParams>(kind, cells, rows, p, residuals, jacobian, velocity_part);
  }
}

}  // namespace knoblab::fit::detail
