// The position-cell compression (apps/fit/src/position_cells.hpp): its
// square root reproduces each cell's Gram matrix, and the cells' residual
// norm, residuals and Jacobian match the per-sample ones to the interpolation
// error.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "../../apps/fit/src/position_cells.hpp"
#include "knoblab/fit/validation_data.hpp"

namespace knoblab::fit {
namespace {

TEST(PositionCells, RootReproducesTheGramMatrix) {
  const FitData d = make_validation_data({});
  std::vector<std::uint32_t> rows(d.size());
  std::iota(rows.begin(), rows.end(), 0u);
  detail::PositionCells cells(d, rows, 0.05);
  for (std::uint32_t i = 0; i < 5000; i += 7) cells.remove(i);  // removal keeps it exact
  cells.factor();
  int checked = 0;
  for (const detail::Cell& c : cells.cells()) {
    if (c.count == 0) continue;
    const detail::CellMatrix g = c.gram.selfadjointView<Eigen::Upper>();
    const detail::CellMatrix rtr = c.root.transpose() * c.root;
    EXPECT_LE((rtr - g).norm(), 1e-9 * g.norm()) << "cell at " << c.center;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(PositionCells, ResidualsAndJacobianMatchThePerSampleOnes) {
  const FitData d = make_validation_data({});
  std::vector<std::uint32_t> rows(d.size());
  std::iota(rows.begin(), rows.end(), 0u);
  const std::vector<double> p = {0.41, 1.4, 1.1, 2.1, 1.4, 0.9, 0.21, 0.8};  // off the truth
  detail::PositionCells cells(d, rows, 0.25 * 0.2);
  cells.factor();
  std::vector<double> r_cells(rows.size()), j_cells(rows.size() * 8);
  std::vector<double> r_exact(rows.size()), j_exact(rows.size() * 8);
  detail::evaluate_cells(ModelKind::Thesis6, cells, rows, p.data(), r_cells, j_cells);
  detail::evaluate_rows(ModelKind::Thesis6, d, rows, p.data(), r_exact, j_exact);
  double worst_r = 0, worst_j = 0, rss = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    worst_r = std::max(worst_r, std::abs(r_cells[i] - r_exact[i]));
    rss += r_exact[i] * r_exact[i];
    for (std::size_t k = 0; k < 8; ++k) {
      worst_j = std::max(worst_j, std::abs(j_cells[i * 8 + k] - j_exact[i * 8 + k]));
    }
  }
  EXPECT_LT(worst_r, 1e-6);  // A = 0.9 N·m: interpolation error ~1e-8·A
  EXPECT_LT(worst_j, 1e-5);
  // The compressed residual norm: Σ over cells of |R·v|².
  double rss_cells = 0;
  for (const detail::Cell& c : cells.cells()) {
    if (c.count == 0) continue;
    double r[detail::kCellCols];
    detail::CellResidual{ModelKind::Thesis6, &c, cells.half_width()}(p.data(), r);
    for (double x : r) rss_cells += x * x;
  }
  EXPECT_NEAR(rss_cells, rss, 1e-9 * rss);
}

}  // namespace
}  // namespace knoblab::fit

namespace knoblab::fit {
namespace {

// The whole fit through the cells and through every sample: the same
// optimum, far inside a standard error.
TEST(PositionCells, CompressedFitEqualsThePerSampleFit) {
  ValidationSpec spec;
  spec.seed = 7;
  const FitData d = make_validation_data(spec);
  FitOptions exact;
  exact.compress = false;
  const FitResult a = fit_knob(d), b = fit_knob(d, exact);
  ASSERT_EQ(a.params.size(), b.params.size());
  for (std::size_t k = 0; k < a.params.size(); ++k) {
    EXPECT_LT(std::abs(a.params[k] - b.params[k]), 1e-3 * b.se[k]) << a.names[k];
    EXPECT_NEAR(a.se[k], b.se[k], 1e-3 * b.se[k]) << a.names[k];
  }
  EXPECT_NEAR(a.rmse_Nm, b.rmse_Nm, 1e-9);
}

}  // namespace
}  // namespace knoblab::fit
