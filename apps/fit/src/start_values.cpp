// Starting values with no hand-given guess (see knob_fit.hpp, steps 1–3).
#include <Eigen/Dense>
#include <algorithm>
#include <array>
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

// Within one direction of motion (ω < 0, = 0, > 0) every linear column is
// α, ω or 1 times a constant, so the normal equations need only each
// direction's sums of the products of (α, ω, 1, τ).
enum Base : std::size_t { kAlpha, kOmega, kOne, kTorque };
constexpr std::size_t kBases = 4;
struct DirectionSums {
  std::array<std::array<double, kBases>, kBases> s{};  // symmetric
};

// Which base column a linear column is, and its factor in each direction
// (−, 0, +): linear_columns in this form.
struct ColumnForm {
  Base base;
  std::array<double, 3> factor;
};
std::vector<ColumnForm> column_forms(ModelKind kind) {
  if (kind == ModelKind::Render4) return {{kAlpha, {1, 1, 1}}, {kOmega, {1, 1, 1}}};
  return {{kAlpha, {1, 1, 1}},   // M_acc
          {kOne, {-1, 0, 0}},    // −C_vel_neg
          {kOmega, {1, 0, 0}},   // B_vel_neg
          {kOne, {0, 0, 1}},     // C_vel_pos
          {kOmega, {0, 0, 1}}};  // B_vel_pos
}

// The sums, summed locally while the rows keep their direction (they do for
// hundreds of rows), so no add waits on a store.
std::array<DirectionSums, 3> direction_sums(const FitData& d, std::span<const std::uint32_t> rows) {
  std::array<DirectionSums, 3> out{};
  std::array<double, 9> run{};  // αα αω α ατ ωω ω ωτ 1 τ
  int current = -1;
  auto flush = [&] {
    if (current < 0) return;
    auto& t = out[static_cast<std::size_t>(current)].s;
    const auto add = [&](Base p, Base q, double v) {
      t[p][q] += v;
      if (p != q) t[q][p] += v;
    };
    add(kAlpha, kAlpha, run[0]), add(kAlpha, kOmega, run[1]), add(kAlpha, kOne, run[2]);
    add(kAlpha, kTorque, run[3]), add(kOmega, kOmega, run[4]), add(kOmega, kOne, run[5]);
    add(kOmega, kTorque, run[6]), add(kOne, kOne, run[7]), add(kOne, kTorque, run[8]);
    run = {};
  };
  for (std::uint32_t i : rows) {
    const double w = d.omega[i], a = d.alpha[i], y = d.torque[i];
    const int g = (w > 0) - (w < 0) + 1;
    if (g != current) flush(), current = g;
    run[0] += a * a, run[1] += a * w, run[2] += a, run[3] += a * y;
    run[4] += w * w, run[5] += w, run[6] += w * y, run[7] += 1, run[8] += y;
  }
  flush();
  return out;
}

// Least squares over the rows with the linear columns, by the normal
// equations. Columns are scaled to unit norm first so that indicator columns
// and accelerations of hundreds of rad/s² condition alike.
Eigen::VectorXd linear_fit(ModelKind kind, const FitData& d, std::span<const std::uint32_t> rows) {
  const std::vector<ColumnForm> cols = column_forms(kind);
  const std::array<DirectionSums, 3> sums = direction_sums(d, rows);
  const auto sum = [&](std::size_t g, Base p, Base q) { return sums[g].s[p][q]; };
  const auto nc = static_cast<Eigen::Index>(cols.size());
  Eigen::MatrixXd xtx = Eigen::MatrixXd::Zero(nc, nc);
  Eigen::VectorXd xty = Eigen::VectorXd::Zero(nc);
  for (Eigen::Index a = 0; a < nc; ++a) {
    const ColumnForm& ca = cols[static_cast<std::size_t>(a)];
    for (std::size_t g = 0; g < 3; ++g) {
      xty(a) += ca.factor[g] * sum(g, ca.base, kTorque);
      for (Eigen::Index b = 0; b < nc; ++b) {
        const ColumnForm& cb = cols[static_cast<std::size_t>(b)];
        xtx(a, b) += ca.factor[g] * cb.factor[g] * sum(g, ca.base, cb.base);
      }
    }
  }
  Eigen::VectorXd scale(nc);
  for (Eigen::Index a = 0; a < nc; ++a) {
    scale(a) = xtx(a, a) > 0 ? std::sqrt(xtx(a, a)) : 1.0;  // a column with no data
  }
  const Eigen::MatrixXd G = scale.cwiseInverse().asDiagonal() * xtx * scale.cwiseInverse().asDiagonal();
  const Eigen::VectorXd g = xty.cwiseQuotient(scale);
  return G.colPivHouseholderQr().solve(g).cwiseQuotient(scale);
}

// Row i's torque less the linear part with coefficients beta: per direction
// of motion that part is c_α·α + c_ω·ω + c_1.
class LinearResidual {
 public:
  LinearResidual(ModelKind kind, const FitData& d, const Eigen::VectorXd& beta) : d_(d) {
    const std::vector<ColumnForm> cols = column_forms(kind);
    for (std::size_t k = 0; k < cols.size(); ++k) {
      for (std::size_t g = 0; g < 3; ++g) {
        coef_[g][cols[k].base] += cols[k].factor[g] * beta(static_cast<Eigen::Index>(k));
      }
    }
  }
  double operator()(std::uint32_t i) const {
    const double w = d_.omega[i];
    const auto& c = coef_[static_cast<std::size_t>((w > 0) - (w < 0) + 1)];
    return d_.torque[i] - (c[kAlpha] * d_.alpha[i] + c[kOmega] * w + c[kOne]);
  }

 private:
  const FitData& d_;
  std::array<std::array<double, kBases>, 3> coef_{};
};

struct Binned {
  std::vector<double> theta, value;
};

// Mean residual per position bin: sorting by position (as the thesis does)
// cuts the periodogram's cost to the bins and averages the noise down. A
// sweep stays in a bin for many rows: sum locally until it leaves.
Binned bin_by_position(const FitData& d, std::span<const std::uint32_t> rows,
                       const LinearResidual& residual, double lo, double hi, std::size_t nbins) {
  std::vector<double> sum_t(nbins, 0.0), sum_r(nbins, 0.0);
  std::vector<std::size_t> count(nbins, 0);
  const double per_rad = static_cast<double>(nbins) / (hi - lo);
  double run_t = 0.0, run_r = 0.0;
  std::size_t run_n = 0, current = nbins;
  auto flush = [&] {
    if (current == nbins) return;
    sum_t[current] += run_t, sum_r[current] += run_r, count[current] += run_n;
    run_t = run_r = 0.0, run_n = 0;
  };
  for (std::uint32_t i : rows) {
    const double th = d.theta[i];
    const std::size_t b = std::min(static_cast<std::size_t>((th - lo) * per_rad), nbins - 1);
    if (b != current) flush(), current = b;
    run_t += th, run_r += residual(i), ++run_n;
  }
  flush();
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
  // 24 steps shrink the bracket (two grid steps) by 1e-5: plenty for a start.
  for (int it = 0; it < 24; ++it) {
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
  const Eigen::VectorXd beta0 = linear_fit(opt.model, d, rows);

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
    const Binned b = bin_by_position(d, rows, LinearResidual(opt.model, d, beta0), lo, hi, nbins);
    const double bin_width = range / static_cast<double>(nbins);
    const double f_lo = std::max(opt.min_detents_per_rev, kPi / range);
    const double f_hi = std::min(opt.max_detents_per_rev, kPi / (2 * bin_width));
    // A quarter of the resolution 2π/range: a peak between grid points loses
    // under 3 % of its power, and the golden-section refine finds it.
    const double df = kPi / (2 * range);
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
