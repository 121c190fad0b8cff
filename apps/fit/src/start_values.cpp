// Starting values with no hand-given guess (see knob_fit.hpp, steps 1–3).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "knoblab/model/periodogram.hpp"
#include "residual.hpp"

namespace knoblab::fit::detail {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kFalseAlarmLimit = 1e-4;
// Detents are the main structure of the position residual, not one line in a
// broad spectrum (smooth position dependence, transients where the sweep
// turns): the peak must explain at least this share of it.
constexpr double kMinDetentShare = 0.25;

// Regressor columns of the model's linear part (everything but the detents),
// in parameter order, for one sample.
int linear_columns(ModelKind kind, double omega, double alpha, double* x) {
  if (kind == ModelKind::Render4) {
    x[0] = alpha;
    x[1] = omega;
    return 2;
  }
  const bool neg = omega < 0, pos = omega > 0;
  x[0] = alpha;
  x[1] = neg ? -1.0 : 0.0;  // −C_vel_neg
  x[2] = neg ? omega : 0.0;
  x[3] = pos ? 1.0 : 0.0;
  x[4] = pos ? omega : 0.0;
  return 5;
}

// Least squares over the rows with the linear columns, by the normal
// equations (at most 5 columns; one pass over the data). Columns are scaled
// to unit norm first so that indicator columns and accelerations of hundreds
// of rad/s² condition alike.
Eigen::VectorXd linear_fit(ModelKind kind, const FitData& d, std::span<const std::uint32_t> rows,
                           Eigen::VectorXd* residual) {
  constexpr int kMax = 5;
  double x[kMax];
  const int ncol = linear_columns(kind, 0.0, 0.0, x);
  double xtx[kMax][kMax] = {}, xty[kMax] = {};
  for (std::uint32_t i : rows) {
    linear_columns(kind, d.omega[i], d.alpha[i], x);
    const double y = d.torque[i];
    for (int a = 0; a < ncol; ++a) {
      xty[a] += x[a] * y;
      for (int b = a; b < ncol; ++b) xtx[a][b] += x[a] * x[b];
    }
  }
  Eigen::MatrixXd G(ncol, ncol);
  Eigen::VectorXd g(ncol), scale(ncol);
  for (int a = 0; a < ncol; ++a) {
    scale(a) = xtx[a][a] > 0 ? std::sqrt(xtx[a][a]) : 1.0;  // a column with no data
  }
  for (int a = 0; a < ncol; ++a) {
    g(a) = xty[a] / scale(a);
    for (int b = a; b < ncol; ++b) G(a, b) = G(b, a) = xtx[a][b] / (scale(a) * scale(b));
  }
  Eigen::VectorXd beta = G.colPivHouseholderQr().solve(g).cwiseQuotient(scale);
  if (residual) {
    residual->resize(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t j = 0; j < rows.size(); ++j) {
      linear_columns(kind, d.omega[rows[j]], d.alpha[rows[j]], x);
      double fitted = 0.0;
      for (int a = 0; a < ncol; ++a) fitted += x[a] * beta(a);
      (*residual)(static_cast<Eigen::Index>(j)) = d.torque[rows[j]] - fitted;
    }
  }
  return beta;
}

struct Binned {
  std::vector<double> theta, value;
};

// Mean residual per position bin: sorting by position (as the thesis does)
// cuts the periodogram's cost to the bins and averages the noise down.
Binned bin_by_position(const FitData& d, std::span<const std::uint32_t> rows,
                       const Eigen::VectorXd& r, double lo, double hi, std::size_t nbins) {
  std::vector<double> sum_t(nbins, 0.0), sum_r(nbins, 0.0);
  std::vector<std::size_t> count(nbins, 0);
  const double w = (hi - lo) / static_cast<double>(nbins);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const double th = d.theta[rows[j]];
    auto b = static_cast<std::size_t>((th - lo) / w);
    b = std::min(b, nbins - 1);
    sum_t[b] += th;
    sum_r[b] += r(static_cast<Eigen::Index>(j));
    ++count[b];
  }
  Binned out;
  for (std::size_t b = 0; b < nbins; ++b) {
    if (count[b] == 0) continue;
    out.theta.push_back(sum_t[b] / static_cast<double>(count[b]));
    out.value.push_back(sum_r[b] / static_cast<double>(count[b]));
  }
  return out;
}

// Golden-section search for the frequency with the most explained variance.
double refine_frequency(const Binned& b, double lo, double hi) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  auto power = [&](double f) { return model::fit_sinusoid(b.theta, b.value, f).power; };
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double p1 = power(x1), p2 = power(x2);
  for (int it = 0; it < 40; ++it) {
    if (p1 > p2) {
      hi = x2, x2 = x1, p2 = p1;
      x1 = hi - g * (hi - lo), p1 = power(x1);
    } else {
      lo = x1, x1 = x2, p1 = p2;
      x2 = lo + g * (hi - lo), p2 = power(x2);
    }
  }
  return (lo + hi) / 2;
}

}  // namespace

StartValues find_start(const FitData& d, std::span<const std::uint32_t> rows,
                       const FitOptions& opt) {
  const int n = param_count(opt.model);
  const int nlin = opt.model == ModelKind::Thesis6 ? 5 : 2;
  StartValues out;
  out.params.assign(static_cast<std::size_t>(n), 0.0);

  // Step 1: the linear part alone, and what it leaves.
  Eigen::VectorXd residual;
  const Eigen::VectorXd beta0 = linear_fit(opt.model, d, rows, &residual);

  double lo = d.theta[rows[0]], hi = lo;
  for (std::uint32_t i : rows) lo = std::min(lo, d.theta[i]), hi = std::max(hi, d.theta[i]);
  const double range = hi - lo;

  // Step 2: periodogram of the position residual over the detent counts the
  // data can show: at least half a cycle over the range, at most four bins a
  // cycle.
  double f_peak = 0.0;
  model::SinusoidFit peak;
  if (opt.detents != FitOptions::Detents::None && range > 1e-3) {
    // Eight bins to the shortest period searched, at most one per 8 samples.
    const double shortest = 2 * kPi / opt.max_detents_per_rev;
    const auto wanted = static_cast<std::size_t>(std::ceil(8 * range / shortest));
    const std::size_t nbins = std::clamp<std::size_t>(std::min(wanted, rows.size() / 8), 64, 4096);
    const Binned b = bin_by_position(d, rows, residual, lo, hi, nbins);
    const double bin_width = range / static_cast<double>(nbins);
    const double f_lo = std::max(opt.min_detents_per_rev, kPi / range);
    const double f_hi = std::min(opt.max_detents_per_rev, kPi / (2 * bin_width));
    const double df = kPi / (4 * range);
    out.period_lo = 1.0 / f_hi;
    out.period_hi = 1.0 / f_lo;
    if (b.theta.size() > 8 && f_hi > f_lo) {
      const model::AngularPeriodogram pg = model::angular_periodogram(b.theta, b.value, f_lo, f_hi, df);
      f_peak = refine_frequency(b, std::max(f_lo, pg.peak.frequency - df),
                                pg.peak.frequency + df);
      peak = model::fit_sinusoid(b.theta, b.value, f_peak);
      out.power = peak.power;
      // Under noise alone a bin periodogram's power p at one frequency
      // exceeds x with probability (1 − x)^((m − 3)/2); independent
      // frequencies are 2π/range apart.
      const double m = static_cast<double>(b.theta.size());
      const double independent = std::max(1.0, (f_hi - f_lo) * range / (2 * kPi));
      const double single = std::pow(1.0 - out.power, (m - 3) / 2);
      out.false_alarm = -std::expm1(independent * std::log1p(-std::min(single, 1.0 - 1e-16)));
    }
  }
  out.detents = opt.detents == FitOptions::Detents::Force
                    ? f_peak > 0
                    : (opt.detents == FitOptions::Detents::Auto && f_peak > 0 &&
                       out.false_alarm < kFalseAlarmLimit && out.power >= kMinDetentShare);

  // Step 3: the other terms from the fit without detents, the detent term
  // from the periodogram's sinusoid at the peak (its fit to the binned
  // residual: A·sin(θ/P + S) + c). Levenberg–Marquardt refines them jointly.
  for (int c = 0; c < nlin; ++c) out.params[static_cast<std::size_t>(c)] = beta0(c);
  const std::size_t a = static_cast<std::size_t>(nlin);  // A_pos, P_pos, S_pos follow
  if (out.detents) {
    out.params[a] = peak.amplitude;
    out.params[a + 1] = 1.0 / f_peak;
    out.params[a + 2] = peak.phase;
  } else {
    out.params[a] = 0.0;
    out.params[a + 1] = 1.0;
    out.params[a + 2] = 0.0;
  }
  return out;
}

}  // namespace knoblab::fit::detail
