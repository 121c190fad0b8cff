// fit_knob: starting values, Levenberg–Marquardt with Ceres, stick band,
// covariance and the summary figures (see knob_fit.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <numeric>

#include "knoblab/fit/ceres_hooks.hpp"
#include "position_cells.hpp"
#include "residual.hpp"

namespace knoblab::fit {

namespace {

using detail::param_count;

struct Solved {
  std::vector<double> params;
  int iterations = 0;
};

// P stays inside the range the detent search covered: outside it a sine is
// a ramp or a constant, which trades off against the friction terms.
struct PeriodBounds {
  double lo = 0.0, hi = 0.0;  // 0: unbounded
};

// The residuals Ceres sees: every sample (exact), or the position cells.
struct Residuals {
  const FitData* d = nullptr;
  std::span<const std::uint32_t> rows;            // exact
  const detail::PositionCells* cells = nullptr;   // compressed
};

template <int N>
void add_cell_blocks(ceres::Problem& problem, ModelKind kind, const detail::PositionCells& cells,
                     double* x) {
  for (const detail::Cell& c : cells.cells()) {
    if (c.count == 0) continue;
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<detail::CellResidual, detail::kCellCols, N>(
            new detail::CellResidual{kind, &c, cells.half_width()}),
        nullptr, x);
  }
}

Solved solve(const Residuals& res, const FitOptions& opt, std::vector<double> start,
             const std::vector<bool>& fitted, PeriodBounds bounds = {}) {
  const int n = param_count(opt.model);
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  if (res.cells) {
    if (n == detail::kThesisParams) add_cell_blocks<detail::kThesisParams>(problem, opt.model, *res.cells, start.data());
    else add_cell_blocks<detail::kRenderParams>(problem, opt.model, *res.cells, start.data());
  } else {
    for (std::size_t s = 0; s < res.rows.size(); s += detail::kChunk) {
      const std::size_t len = std::min(detail::kChunk, res.rows.size() - s);
      problem.AddResidualBlock(
          detail::make_chunk_cost(opt.model, *res.d, res.rows.subspan(s, len)).release(), nullptr,
          start.data());
    }
  }
  std::vector<int> held;
  for (int k = 0; k < n; ++k) {
    if (!fitted[static_cast<std::size_t>(k)]) held.push_back(k);
  }
  if (!held.empty()) problem.SetManifold(start.data(), new ceres::SubsetManifold(n, held));
  const int p_index = n - 2;  // P_pos
  if (bounds.hi > bounds.lo && fitted[static_cast<std::size_t>(p_index)]) {
    auto& P = start[static_cast<std::size_t>(p_index)];
    P = std::clamp(P, bounds.lo, bounds.hi);
    problem.SetParameterLowerBound(start.data(), p_index, bounds.lo);
    problem.SetParameterUpperBound(start.data(), p_index, bounds.hi);
  }

  ceres::Solver::Options so;
  // 8 parameters: the normal equations are 8 × 8, far cheaper than a QR of
  // the stacked Jacobian and well conditioned at this size.
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  so.max_num_iterations = opt.max_iterations;
  so.num_threads = res.cells ? 1 : opt.threads;  // cells: too little work to share
  so.function_tolerance = 1e-12;
  so.parameter_tolerance = 1e-12;
  so.gradient_tolerance = 1e-14;
  so.logging_type = ceres::SILENT;
  CancelCallback cancel(opt.hooks);
  so.callbacks.push_back(&cancel);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  opt.hooks.check();  // an aborted solve is no failure to report
  if (!summary.IsSolutionUsable()) {
    throw FitDataError("the fit did not converge: " + summary.message);
  }
  return {std::move(start), summary.num_successful_steps + summary.num_unsuccessful_steps};
}

// A ≥ 0 and S in (−π, π]: one spelling for every equivalent detent term.
void canonical_detents(std::vector<double>& p) {
  const std::size_t a = p.size() - 3;  // A_pos, P_pos, S_pos are the last three
  model::Detents<double> d;
  d.A = p[a], d.P = p[a + 1], d.S = p[a + 2];
  d = model::canonical(d);
  p[a] = d.A, p[a + 2] = d.S;
}

// Rows for the detent search and starting values: where the knob slides
// briskly, |θ̇| at least a tenth of the 95th percentile speed. Stuck samples
// and reversals carry torque the sliding law does not explain, all at a few
// positions (where the sweep turns), which a periodogram over position would
// take for detents.
std::vector<std::uint32_t> moving_rows(const FitData& d, std::span<const std::uint32_t> rows) {
  // The strided rows' speeds: what strided_quantile would take of all of them.
  const std::size_t stride = detail::summary_stride(rows.size());
  std::vector<double> speed;
  speed.reserve(rows.size() / stride + 1);
  for (std::size_t j = 0; j < rows.size(); j += stride) speed.push_back(std::abs(d.omega[rows[j]]));
  const double threshold = 0.1 * detail::strided_quantile(speed, 0.95);
  // Starting values need no more than ~50 000 rows: evenly strided beyond
  // that (Levenberg–Marquardt then uses every row).
  const std::size_t every = std::max<std::size_t>(1, rows.size() / 50000);
  std::vector<std::uint32_t> kept, all;
  kept.reserve(rows.size() / every + 1);
  all.reserve(rows.size() / every + 1);
  for (std::size_t j = 0; j < rows.size(); j += every) {
    all.push_back(rows[j]);
    if (std::abs(d.omega[rows[j]]) >= threshold) kept.push_back(rows[j]);
  }
  // Too few left (a capture that mostly stands still): search them all.
  return kept.size() < all.size() / 2 ? all : kept;
}

// Residuals (model − measured) and velocity parts of single rows at fixed
// parameters: through the cells, or sample by sample.
class RowModel {
 public:
  RowModel(const Residuals& res, ModelKind kind, const std::vector<double>& p)
      : d_(res.d), cells_(res.cells), thesis_(detail::as_thesis(kind, p.data())) {
    if (cells_) cell_model_ = detail::cell_model(kind, *cells_, p.data(), false);
  }
  double residual(std::uint32_t i) const {
    if (cells_) [[likely]] return cell_model_.residual(i);
    return thesis_.torque(d_->kinematics(i)) - d_->torque[i];
  }
  double velocity_part(std::uint32_t i) const {
    if (cells_) [[likely]] return cell_model_.velocity_part(i);
    return thesis_.parts(d_->kinematics(i)).vel;
  }

 private:
  const FitData* d_;
  const detail::PositionCells* cells_;
  model::ThesisModel<double> thesis_;
  detail::CellModel cell_model_;
};

// Rows whose residual, residual(j) for rows[j], lies within five robust
// standard deviations. The median and MAD come from evenly strided rows, as
// strided_quantile takes them.
template <class Residual>
std::vector<std::uint32_t> within_robust_range(std::span<const std::uint32_t> rows,
                                               const Residual& residual) {
  const std::size_t stride = detail::summary_stride(rows.size());
  std::vector<double> e;
  e.reserve(rows.size() / stride + 1);
  for (std::size_t j = 0; j < rows.size(); j += stride) e.push_back(residual(j));
  const double med = detail::strided_quantile(e, 0.5);
  for (double& x : e) x = std::abs(x - med);
  const double limit = 5.0 * 1.4826 * detail::strided_quantile(e, 0.5);
  if (!(limit > 0)) return {rows.begin(), rows.end()};
  std::vector<std::uint32_t> kept;
  kept.reserve(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    if (std::abs(residual(j) - med) <= limit) kept.push_back(rows[j]);
  }
  return kept;
}

// Leaves the rows not in `kept` out of the residuals (both sorted).
void keep_only(Residuals& res, detail::PositionCells* cells, std::vector<std::uint32_t>& rows,
               std::vector<std::uint32_t> kept) {
  if (cells) {
    std::size_t k = 0;
    for (std::uint32_t i : rows) {
      if (k < kept.size() && kept[k] == i) ++k;
      else cells->remove(i);
    }
    cells->factor();
  }
  rows = std::move(kept);
  res.rows = rows;
}

// Wall time since the last call, seconds: fit_knob's phase clock.
class Lap {
 public:
  double operator()() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

FitResult fit_knob(const FitData& d, const FitOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  Lap lap;
  if (d.size() < 16) throw FitDataError("too few samples to fit");
  const std::size_t n = static_cast<std::size_t>(param_count(opt.model));
  std::vector<std::uint32_t> rows(d.size());
  std::iota(rows.begin(), rows.end(), 0u);

  FitResult r;
  r.model = opt.model;
  r.axis = d.axis;
  r.names = param_names(opt.model);
  const std::size_t a = n - 3;  // A_pos, P_pos, S_pos are the last three

  std::vector<double> start;
  PeriodBounds bounds;
  if (opt.start) {
    if (opt.start->size() != n) throw std::invalid_argument("start vector has the wrong size");
    start = *opt.start;
    r.detents = start[a] != 0.0;
  } else {
    opt.hooks.report("searching detents");
    const detail::StartValues sv = detail::find_start(d, moving_rows(d, rows), opt);
    opt.hooks.check();
    start = sv.params;
    bounds = {sv.period_lo, sv.period_hi};
    r.detents = sv.detents;
    r.detent_power = sv.power;
    r.detent_false_alarm = sv.false_alarm;
  }
  r.phases.start = lap();
  r.fitted.assign(n, true);
  if (!r.detents) r.fitted[a] = r.fitted[a + 1] = r.fitted[a + 2] = false;
  if (rows.size() <= n + 1) throw FitDataError("too few samples for the model's parameters");

  // Cells a quarter of P wide (or one bin: no detents). Should the fit
  // shorten P by more than a tenth, the cells are rebuilt for the new P and
  // the fit repeated, so the interpolant stays as exact as documented.
  std::optional<detail::PositionCells> cells;
  double cells_P = 0.0;  // the P the cells were built for
  Residuals res{&d, rows, nullptr};
  const auto build_cells = [&](double P) {
    cells.emplace(d, rows, r.detents ? 0.25 * P : 0.0);
    cells->factor();
    cells_P = P;
    res.cells = &*cells;
  };
  opt.hooks.report("fitting");
  if (opt.compress) build_cells(std::abs(start[a + 1]));
  detail::PositionCells* cp = cells ? &*cells : nullptr;
  r.phases.cells = lap();

  const auto refit = [&](const std::vector<double>& from) {
    Solved out = solve(res, opt, from, r.fitted, bounds);
    r.iterations += out.iterations;
    if (cells && r.detents && std::abs(out.params[a + 1]) < 0.9 * cells_P) {
      build_cells(std::abs(out.params[a + 1]));
      cp = &*cells;
      Solved again = solve(res, opt, out.params, r.fitted, bounds);
      r.iterations += again.iterations;
      out = std::move(again);
    }
    return out;
  };
  Solved s = refit(start);
  r.phases.solve = lap();
  // Residuals (model − measured) of rows at s.params, while nothing changed them.
  std::vector<double> e;
  if (opt.stick_band && opt.model == ModelKind::Thesis6) {
    opt.hooks.report("stick band");
    const RowModel model(res, opt.model, s.params);
    e.resize(rows.size());
    for (std::size_t j = 0; j < rows.size(); ++j) e[j] = model.residual(rows[j]);
    r.stick = detail::estimate_stick_band(
        d, rows, e, [&](std::size_t j) { return model.velocity_part(rows[j]); });
    if (r.stick) {
      // The sliding law does not hold inside the band: fit without it.
      std::vector<std::uint32_t> kept;
      kept.reserve(rows.size());
      for (std::uint32_t i : rows) {
        if (std::abs(d.omega[i]) >= r.stick->dv) kept.push_back(i);
      }
      if (kept.size() > 10 * n) {
        e.clear();
        keep_only(res, cp, rows, std::move(kept));
        r.phases.stick_band = lap();
        s = refit(s.params);
        r.phases.solve += lap();
      }
    }
    r.phases.stick_band += lap();
  }
  // Breakaway transients: just outside the band a compliant gripper rings,
  // with accelerations far above the sweep's, so a handful of samples the
  // sliding law cannot describe would set M. Leave out what lies beyond five
  // robust standard deviations (MAD) and fit once more.
  if (opt.trim_outliers) {
    opt.hooks.report("outliers");
    std::vector<std::uint32_t> kept;
    if (e.size() == rows.size()) {
      kept = within_robust_range(rows, [&](std::size_t j) { return e[j]; });
    } else {
      const RowModel model(res, opt.model, s.params);
      kept = within_robust_range(rows, [&](std::size_t j) { return model.residual(rows[j]); });
    }
    r.outliers = rows.size() - kept.size();
    if (r.outliers > 0 && kept.size() > 10 * n) {
      e.clear();
      keep_only(res, cp, rows, std::move(kept));
      r.phases.trim = lap();
      s = refit(s.params);
      r.phases.solve += lap();
    }
    r.phases.trim += lap();
  }
  if (r.detents) canonical_detents(s.params);
  r.params = s.params;
  opt.hooks.check();
  opt.hooks.report("intervals");

  const detail::CovarianceEstimate cov =
      cells ? detail::covariance_from_cells(opt.model, *cells, rows, r.params.data(), r.fitted, e)
            : detail::estimate_covariance(opt.model, d, rows, r.params.data(), r.fitted);
  r.covariance = cov.covariance;
  r.se = cov.se;
  r.t95 = cov.t95;
  r.covariance_inflation = cov.inflation;
  r.ci95.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double h = r.t95 * r.se[k];
    r.ci95[k] = {r.params[k] - h, r.params[k] + h};
  }

  // Summary figures over the fitted samples.
  const double m = static_cast<double>(rows.size());
  std::size_t k_free = 0;
  for (bool f : r.fitted) k_free += f ? 1 : 0;
  double sum = 0.0, sum2 = 0.0;  // of τ − τ₀, shifted against cancellation
  const double shift = d.torque[rows.front()];
  for (std::uint32_t i : rows) {
    const double y = d.torque[i] - shift;
    sum += y, sum2 += y * y;
  }
  const double tss = std::max(0.0, sum2 - sum * sum / m);
  r.samples = rows.size();
  r.rmse_Nm = std::sqrt(cov.rss / m);
  r.fit_percent = tss > 0 ? 100.0 * (1.0 - std::sqrt(cov.rss / tss)) : 0.0;
  r.bic = m * std::log(cov.rss / m) + static_cast<double>(k_free) * std::log(m);
  r.residual_sd = std::sqrt(cov.rss / (m - static_cast<double>(k_free)));
  r.ci95_torque_Nm = r.t95 * cov.curve_sd_mean;
  r.phases.covariance = lap();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

model::ThesisModel<double> thesis_model(const FitResult& r) {
  return detail::as_thesis(r.model, r.params.data());
}

}  // namespace knoblab::fit
