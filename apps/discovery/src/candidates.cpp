#include "candidates.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "knoblab/fit/axis_units.hpp"
#include "knoblab/model/effect_table.hpp"
#include "knoblab/model/periodogram.hpp"
#include "knoblab/model/quantile.hpp"

namespace knoblab::discovery::detail {

namespace {

constexpr double kPi = std::numbers::pi;
// How much lower a candidate's richer form must put the training RMS to be
// taken over its simpler one: DiscrepancyOptions::parsimony_margin's
// default, one bar for a richer form and a richer name.
constexpr double kRicherFormMargin = 0.02;

template <typename... A>
std::string format(const char* f, A... a) {
  std::string out(static_cast<std::size_t>(std::snprintf(nullptr, 0, f, a...)), '\0');
  std::snprintf(out.data(), out.size() + 1, f, a...);
  return out;
}

// Least squares of the residual on the given columns (one per regressor).
std::vector<double> regress(const std::vector<std::vector<double>>& cols,
                            const std::vector<double>& r, double* sse = nullptr) {
  const auto n = static_cast<Eigen::Index>(r.size());
  const auto k = static_cast<Eigen::Index>(cols.size());
  Eigen::MatrixXd X(n, k);
  for (Eigen::Index c = 0; c < k; ++c)
    for (Eigen::Index i = 0; i < n; ++i) X(i, c) = cols[static_cast<std::size_t>(c)][static_cast<std::size_t>(i)];
  const Eigen::Map<const Eigen::VectorXd> y(r.data(), n);
  const Eigen::VectorXd beta = X.colPivHouseholderQr().solve(y);
  if (sse) *sse = (y - X * beta).squaredNorm();
  return {beta.data(), beta.data() + k};
}

// y binned over position (mean per bin), for a periodogram.
struct Binned {
  std::vector<double> theta, y;
  double range = 0.0;
};
Binned bin(const fit::FitData& d, std::span<const std::size_t> rows, const std::vector<double>& y,
           std::size_t nbins = 1024) {
  double lo = d.theta[rows[0]], hi = lo;
  for (const std::size_t i : rows) lo = std::min(lo, d.theta[i]), hi = std::max(hi, d.theta[i]);
  Binned b;
  b.range = hi - lo;
  if (!(b.range > 0)) return b;
  std::vector<double> st(nbins, 0.0), sy(nbins, 0.0), c(nbins, 0.0);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const double th = d.theta[rows[j]];
    const auto k = std::min(nbins - 1, static_cast<std::size_t>((th - lo) / b.range * static_cast<double>(nbins)));
    st[k] += th, sy[k] += y[j], c[k] += 1.0;
  }
  for (std::size_t k = 0; k < nbins; ++k) {
    if (c[k] == 0) continue;
    b.theta.push_back(st[k] / c[k]);
    b.y.push_back(sy[k] / c[k]);
  }
  return b;
}

// The strongest sinusoid of y over position, frequencies (cycles/rev) at
// least `f_min`, skipping the main lobe (±1 resolution) around each of `avoid`.
std::optional<model::SinusoidFit> strongest_periodic(const Binned& b, double f_min,
                                                     const std::vector<double>& avoid) {
  if (b.theta.size() < 16 || !(b.range > 0)) return std::nullopt;
  const double resolution = 2 * kPi / b.range;
  const double f_hi = 0.25 * static_cast<double>(b.theta.size()) * resolution;  // 4 bins a cycle
  const double f_lo = std::max(f_min, 0.5 * resolution);
  if (!(f_hi > f_lo)) return std::nullopt;
  const model::AngularPeriodogram pg =
      model::angular_periodogram(b.theta, b.y, f_lo, f_hi, resolution / 4);
  double best = -1.0, f_best = 0.0;
  for (std::size_t k = 0; k < pg.frequency.size(); ++k) {
    const double f = pg.frequency[k];
    bool skip = false;
    // Inside a modelled peak's main lobe (its first zeros at ±1 resolution;
    // a little less, so a neighbour one resolution away stays findable).
    for (const double a : avoid) skip = skip || std::abs(f - a) < 0.75 * resolution;
    if (!skip && pg.power[k] > best) best = pg.power[k], f_best = f;
  }
  if (best <= 0) return std::nullopt;
  return model::fit_sinusoid(b.theta, b.y, f_best);
}

std::vector<double> column(std::span<const std::size_t> rows,
                           auto f) {
  std::vector<double> c(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) c[j] = f(rows[j]);
  return c;
}

ExtendedModel with(const ExtendedModel& m, ActiveEffect e) {
  ExtendedModel out = m;
  out.effects.push_back(std::move(e));
  return out;
}

// Searches an operator's setting on a grid (short fits), refines it between
// the grid's neighbours (the setting's own scale: ±15 %, ±30 %), then fits
// the best one fully.
std::optional<ExtendedModel> grid_search(EffectId id, const std::vector<double>& settings,
                                         const ExtendedModel& m, const fit::FitData& d,
                                         std::span<const std::size_t> train) {
  std::optional<ExtendedModel> best;
  double best_rmse = 0.0, best_setting = 0.0;
  const auto try_setting = [&](double s) {
    ExtendedModel c = with(m, {id, {}, s});
    const FitReport r = fit_extended(c, d, train, 6);
    if (!best || r.rmse < best_rmse) best = std::move(c), best_rmse = r.rmse, best_setting = s;
  };
  for (const double s : settings) try_setting(s);
  if (!best) return best;
  const double centre = best_setting;
  for (const double f : {0.7, 0.85, 1.15, 1.3}) try_setting(centre * f);
  fit_extended(*best, d, train, 40);
  return best;
}

// RMS of the residuals r over the rows where they and `alongside` are both
// numbers (NaN: the model does not predict that row); +∞ with no such row.
double rms_where(const std::vector<double>& r, const std::vector<double>& alongside) {
  double ss = 0.0, n = 0.0;
  for (std::size_t j = 0; j < r.size(); ++j) {
    if (std::isnan(r[j]) || std::isnan(alongside[j])) continue;
    ss += r[j] * r[j];
    n += 1.0;
  }
  return n > 0.0 ? std::sqrt(ss / n) : std::numeric_limits<double>::infinity();
}

// Of two forms of one effect, the one with the smaller residual on the rows
// both predict.
std::optional<ExtendedModel> better_form(std::optional<ExtendedModel> a, std::optional<ExtendedModel> b,
                                         const fit::FitData& d, std::span<const std::size_t> train) {
  if (!a || !b) return a ? std::move(a) : std::move(b);
  const std::vector<double> ra = residuals(*a, d, train), rb = residuals(*b, d, train);
  return rms_where(rb, ra) < rms_where(ra, rb) ? std::move(b) : std::move(a);
}

// A compliance search's grid: ringing frequencies (Hz) at a starting damping
// ratio, then damping ratios at the best, then stiffness factors at that.
struct ComplianceGrid {
  std::vector<double> ringing_hz;
  double start_zeta;
  std::vector<double> zetas, refine;
};

// Compliance has two settings: the coupling's stiffness k and its lag c/k.
// k on a grid spanning the knob's ringing from 30 Hz to 1 kHz (k = M·ω²;
// stiffer than that is rigid here) at a middling damping ratio ζ = 0.5
// (c/k = 2ζ/ω); then ζ at the best k from undamped to overdamped; then k
// refined at that ζ; then the best fitted fully. Two forms: the knob's
// motion read off the measured torque (the twist τ/k: stiff couplings), or
// simulated behind the coupling (coupled_knob.hpp: soft ones), whose sharp
// ring takes a grid twice as fine, started at the light damping a gripper
// has. Both forms are candidates, and the held-out rows choose between them
// as between effects: on the training rows the twist form wins by fitting
// the noise its τ̈/k brings into the knob's acceleration.
std::optional<ExtendedModel> compliance_form(const ExtendedModel& m, const fit::FitData& d,
                                             std::span<const std::size_t> train, bool simulated) {
  const double M = std::abs(m.base[model::kM_acc]);
  if (!(M > 0.0)) return std::nullopt;
  const ComplianceGrid grid =
      simulated ? ComplianceGrid{{30.0, 42.0, 60.0, 85.0, 120.0, 170.0, 250.0, 350.0, 500.0, 700.0, 1000.0},
                                 0.2,
                                 {0.05, 0.1, 0.35, 0.7, 1.0},
                                 {0.8, 0.9, 1.1, 1.25}}
                : ComplianceGrid{{30.0, 60.0, 120.0, 250.0, 500.0, 1000.0}, 0.5, {0.0, 0.2, 1.0, 2.0},
                                 {0.7, 0.85, 1.15, 1.3}};
  // The simulated form is judged on the rows the model it extends
  // describes, as discovery will judge it; the twist form on its own.
  const std::vector<double> described = simulated ? residuals(m, d, train) : std::vector<double>{};
  const auto judged = [&](const FitReport& r) { return simulated ? rms_where(r.residuals, described) : r.rmse; };
  std::optional<ExtendedModel> best;
  double best_rmse = 0.0, best_k = 0.0, best_zeta = grid.start_zeta;
  const auto try_setting = [&](double k, double zeta) {
    ActiveEffect e{EffectId::Compliance, {}, k};
    e.lag_s = 2.0 * zeta / std::sqrt(k / M);
    e.simulated = simulated;
    ExtendedModel c = with(m, std::move(e));
    const double rmse = judged(fit_extended(c, d, train, 6));
    if (!best || rmse < best_rmse) best = std::move(c), best_rmse = rmse, best_k = k, best_zeta = zeta;
  };
  for (const double f : grid.ringing_hz) try_setting(M * std::pow(2 * kPi * f, 2), grid.start_zeta);
  const double k = best_k;
  for (const double zeta : grid.zetas) try_setting(k, zeta);
  const double zeta = best_zeta;
  for (const double f : grid.refine) try_setting(k * f, zeta);
  const FitReport fitted = fit_extended(*best, d, train, 40);
  // The base's terms, fitted as if the coupling were rigid, refitted on the
  // simulated knob's motion, twice; kept where the rows are better
  // predicted. Only with rows the law describes to fit them on: with none
  // the fit has nothing to move.
  const auto sliding_rows = [&](const ExtendedModel& c) {
    std::size_t n = 0;
    for (const RowInputs& r : row_inputs(d, train, c)) n += r.described ? 1 : 0;
    return n;
  };
  if (simulated && sliding_rows(*best) >= 10 * static_cast<std::size_t>(kMaxParams)) {
    ExtendedModel refit = *best;
    refit.refit_behind_coupling = true;
    FitReport last;
    for (int pass = 0; pass < 2; ++pass) last = fit_extended(refit, d, train, 20);
    refit.refit_behind_coupling = false;
    if (judged(last) < judged(fitted)) best = std::move(refit);
  }
  return best;
}

double base_period(const ExtendedModel& m) { return std::abs(m.base[model::kP_pos]); }
bool base_has_detents(const ExtendedModel& m) {
  return m.has_detents();
}

// The base's detent search takes the strongest sinusoid over position. A
// profile whose second harmonic outweighs its fundamental (two dips of
// unequal depth per detent) leaves the base with that harmonic, and the
// detents' own period is twice the base's: the shape with the base's term as
// its second harmonic and the fundamental from the residual. Only where the
// base's detents are fitted here and the doubled period still repeats
// (≥ 1.5 cycles per revolution, two periods over the travel).
std::optional<ExtendedModel> halved_detents(const ExtendedModel& m, const fit::FitData& d,
                                            std::span<const std::size_t> train, const std::vector<double>& r) {
  if (!m.base_fitted[model::kP_pos] || !m.base_fitted[model::kA_pos]) return std::nullopt;
  const double period = 2.0 * m.base[model::kP_pos];  // P, in rad per radian of phase
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const std::size_t i : train) lo = std::min(lo, d.theta[i]), hi = std::max(hi, d.theta[i]);
  if (!repeats_as_detents(period, hi - lo)) return std::nullopt;
  ExtendedModel h = m;
  h.base[model::kP_pos] = period;
  h.base[model::kS_pos] = 0.5 * m.base[model::kS_pos];
  const auto phase = [&](std::size_t i) { return d.theta[i] / period + h.base[model::kS_pos]; };
  const auto b = regress({column(train, [&](std::size_t i) { return std::sin(phase(i)); })}, r);
  h.base[model::kA_pos] = b[0];
  std::vector<double> shape(2 * (kShapeHarmonics - 1), 0.0);
  shape[0] = m.base[model::kA_pos];  // a₂: the base's term, now the second harmonic
  ExtendedModel out = with(h, {EffectId::DetentShape, std::move(shape), 0.0});
  fit_extended(out, d, train, 40);
  return out;
}

// Effect `id` in its one form (compliance has two: candidate_forms).
std::optional<ExtendedModel> fit_candidate(EffectId id, const ExtendedModel& m,
                                           const fit::FitData& d,
                                           std::span<const std::size_t> train,
                                           const std::vector<double>& r) {
  auto theta = [&](std::size_t i) { return d.theta[i]; };
  std::optional<ExtendedModel> c;
  switch (id) {
    case EffectId::Offset: {
      double mean = 0.0;
      for (const double v : r) mean += v / static_cast<double>(r.size());
      c = with(m, {id, {mean}, 0.0});
      break;
    }
    case EffectId::Gravity: {
      const auto b = regress({column(train, [&](std::size_t i) { return std::sin(theta(i)); }),
                              column(train, [&](std::size_t i) { return std::cos(theta(i)); })},
                             r);
      c = with(m, {id, {std::hypot(b[0], b[1]), std::atan2(b[1], b[0])}, 0.0});
      break;
    }
    case EffectId::Spring: {
      double mean = 0.0;
      for (const std::size_t i : train) mean += d.theta[i] / static_cast<double>(train.size());
      const auto b = regress({column(train, [&](std::size_t i) { return d.theta[i] - mean; }),
                              column(train, [&](std::size_t i) { return std::pow(d.theta[i] - mean, 3); })},
                             r);
      // The centre is fitted with the stiffnesses: about a wrong centre a
      // hardening spring leaves a quadratic torque that gravity would take up.
      // A linear spring (K₃ held at 0) is the simpler form; the cubic one
      // must earn its parameter by the margin a richer name must win by
      // (kRicherFormMargin): a BIC alone lets the cubic take up a sliver of
      // curvature the base leaves, and the third parameter then loses the
      // name to gravity's two.
      if (m.flat().size() + 3 > static_cast<std::size_t>(kMaxParams)) return std::nullopt;  // no room
      const auto b1 = regress({column(train, [&](std::size_t i) { return d.theta[i] - mean; })}, r);
      ActiveEffect linear{id, {b1[0], 0.0, mean}, 0.0};
      linear.fixed = 1u << 1;
      ExtendedModel lin = with(m, linear), cub = with(m, {id, {b[0], b[1], mean}, 0.0});
      const double n = static_cast<double>(train.size());
      const auto bic = [&](ExtendedModel& x, double& rmse) {
        rmse = fit_extended(x, d, train, 40).rmse;
        const std::vector<bool> free = x.free_mask();
        const auto k = static_cast<double>(std::count(free.begin(), free.end(), true));
        return n * std::log(std::max(rmse * rmse, 1e-300)) + k * std::log(n);
      };
      double rmse_lin = 0.0, rmse_cub = 0.0;
      const double bic_lin = bic(lin, rmse_lin), bic_cub = bic(cub, rmse_cub);
      const bool cubic = bic_cub < bic_lin && rmse_cub < (1.0 - kRicherFormMargin) * rmse_lin;
      c = cubic ? std::move(cub) : std::move(lin);
      break;
    }
    case EffectId::PeriodicTorque: {
      // Away from the detents and their harmonics, and above once per
      // revolution (gravity's).
      // Harmonics detent_shape can model are left to it; higher ones (a 5th
      // of cogging) may be found here and are said to be harmonics.
      std::vector<double> avoid;
      if (base_has_detents(m)) {
        for (std::size_t k = 1; k <= kShapeHarmonics; ++k) avoid.push_back(static_cast<double>(k) / base_period(m));
      }
      for (const ActiveEffect& e : m.effects) {  // periodic torques found already
        if (e.id == EffectId::PeriodicTorque) avoid.push_back(1.0 / std::abs(e.params[1]));
      }
      const auto peak = strongest_periodic(bin(d, train, r), 1.5, avoid);
      if (!peak) return std::nullopt;
      c = with(m, {id, {peak->amplitude, 1.0 / peak->frequency, peak->phase}, 0.0});
      break;
    }
    case EffectId::DetentShape:
      if (!base_has_detents(m)) return std::nullopt;
      c = with(m, {id, std::vector<double>(2 * (kShapeHarmonics - 1), 0.0), 0.0});
      fit_extended(*c, d, train, 40);
      c = better_form(std::move(c), halved_detents(m, d, train, r), d, train);
      break;
    case EffectId::Stribeck: {
      std::vector<double> speed;
      for (const std::size_t i : train) speed.push_back(std::abs(d.omega[i]));
      const double s95 = model::quantile(speed, 0.95);
      double best_sse = 0.0;
      std::vector<double> start;
      // Starting speeds over the brisk range, and down to the slowest rows
      // when they are given (the low-speed pass: bearings' 0.01 rad/s).
      std::vector<double> speeds;
      for (const double f : {0.02, 0.05, 0.1, 0.2, 0.4}) speeds.push_back(f * s95);
      const double slowest = model::quantile(speed, 0.01);
      for (double v = 0.01 * s95; v > 2 * slowest && v > 1e-3; v /= 2.5) speeds.push_back(v);
      for (const double vs : speeds) {
        double sse = 0.0;
        const auto b = regress({column(train, [&](std::size_t i) {
                                 const double x = d.omega[i] / vs;
                                 return model::sgn(d.omega[i]) * std::exp(-x * x);
                               })},
                               r, &sse);
        if (start.empty() || sse < best_sse) best_sse = sse, start = {b[0], vs};
      }
      c = with(m, {id, start, 0.0});
      break;
    }
    case EffectId::NonlinearDamping: {
      double best_sse = 0.0;
      std::vector<double> start;
      for (const double p : {0.5, 2.0}) {
        double sse = 0.0;
        const auto b = regress({column(train, [&](std::size_t i) {
                                 return model::sgn(d.omega[i]) * std::pow(std::abs(d.omega[i]), p);
                               })},
                               r, &sse);
        if (start.empty() || sse < best_sse) best_sse = sse, start = {b[0], p};
      }
      c = with(m, {id, start, 0.0});
      break;
    }
    case EffectId::PositionFriction: {
      // Moving one way only, sgn(θ̇)·f(θ) is a periodic torque: leave the
      // name to the simpler effect.
      std::size_t forward = 0;
      for (const std::size_t i : train) forward += d.omega[i] > 0 ? 1 : 0;
      if (std::min(forward, train.size() - forward) < train.size() / 20) return std::nullopt;
      std::vector<double> rs(r.size());
      for (std::size_t j = 0; j < r.size(); ++j) rs[j] = r[j] * model::sgn(d.omega[train[j]]);
      const auto peak = strongest_periodic(bin(d, train, rs), 0.5, {});
      if (!peak) return std::nullopt;
      c = with(m, {id, {peak->amplitude, 1.0 / peak->frequency, peak->phase}, 0.0});
      break;
    }
    case EffectId::Drift: {
      double t_mid = 0.0;
      for (const std::size_t i : train) t_mid += d.t[i] / static_cast<double>(train.size());
      const auto b = regress({column(train, [&](std::size_t i) { return model::sgn(d.omega[i]) * (d.t[i] - t_mid); })}, r);
      c = with(m, {id, {b[0]}, t_mid});
      break;
    }
    case EffectId::TimeDelay:
      return grid_search(id, {-5e-3, -2e-3, -1e-3, -5e-4, -2e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3}, m,
                         d, train);
    case EffectId::Saturation: {
      // Only when the torque has flat tops: samples sitting on its extreme
      // value. Looked for in the torque as recorded, where a clipped
      // sensor's samples equal the limit (hundreds of rows; one or two reach
      // an unclipped signal's peak); the low-pass rings at each corner and
      // lifts the filtered extreme off the flat.
      const std::vector<double>& tau = d.torque_recorded.size() == d.size() ? d.torque_recorded : d.torque;
      double top = 0.0;
      for (const std::size_t i : train) top = std::max(top, std::abs(tau[i]));
      std::size_t at_top = 0;
      for (const std::size_t i : train) at_top += std::abs(tau[i]) >= (1.0 - 1e-4) * top ? 1 : 0;
      if (at_top < std::max<std::size_t>(5, train.size() / 1000) || !(top > 0)) return std::nullopt;
      c = with(m, {id, {}, top});
      break;
    }
    case EffectId::Backlash:
      return grid_search(id, {0.5e-3, 1e-3, 2e-3, 4e-3, 8e-3, 16e-3}, m, d, train);
    case EffectId::Hysteresis:
      return grid_search(id, {1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2}, m, d, train);
    case EffectId::Endstop: {
      // A stop engages only at the extremes of the travel. Its position on a
      // fine grid over the outer |θ| (a bin under 1 % of that span), and at
      // each the stiffness by regression on the depth beyond it, in two
      // forms: a mechanical stop climbs on, K·depth; a rendered wall tops
      // out, K·min(depth, w) with its ramp's width w = T/K on a grid too.
      // The best of each is fitted fully; the one that tops out has a
      // parameter more and must lower the training RMS by the margin a
      // richer form must win by (kRicherFormMargin), and the BIC, as a
      // spring's cubic term must.
      if (m.flat().size() + 2 > static_cast<std::size_t>(kMaxParams)) return std::nullopt;  // no room
      std::vector<double> mag;
      for (const std::size_t i : train) mag.push_back(std::abs(d.theta[i]));
      const double from = model::quantile(mag, 0.2), to = model::quantile(mag, 0.995);
      const double deepest = *std::max_element(mag.begin(), mag.end());
      if (!(to > from)) return std::nullopt;
      struct Start {
        double sse = std::numeric_limits<double>::infinity(), at = 0.0, K = 0.0, width = 0.0;
      };
      Start climbing, topping;
      constexpr int kSteps = 120;
      for (int k = 0; k <= kSteps; ++k) {
        const double at = from + (to - from) * k / kSteps;
        for (const double share : {0.0, 0.05, 0.1, 0.2, 0.35, 0.5, 0.7}) {
          // share 0: the stop climbs on; else its ramp ends that share of
          // the way to the deepest point.
          const double width = share > 0 ? share * (deepest - at) : std::numeric_limits<double>::infinity();
          double sxx = 0.0, sxr = 0.0, srr = 0.0;
          for (std::size_t j = 0; j < train.size(); ++j) {
            const double th = d.theta[train[j]];
            const double x = std::abs(th) > at ? std::copysign(std::min(std::abs(th) - at, width), th) : 0.0;
            sxx += x * x, sxr += x * r[j], srr += r[j] * r[j];
          }
          if (!(sxx > 0.0) || !(sxr > 0.0)) continue;  // nothing beyond, or a stop that pushes outwards
          const double sse = srr - sxr * sxr / sxx;
          Start& best = share > 0 ? topping : climbing;
          if (sse < best.sse) best = {sse, at, sxr / sxx, width};
        }
      }
      const double n = static_cast<double>(train.size());
      const auto fitted = [&](const Start& s, bool tops_out, double& rmse, double& bic) -> std::optional<ExtendedModel> {
        if (!std::isfinite(s.sse)) return std::nullopt;
        std::vector<double> q{s.K};
        if (tops_out) q.push_back(s.K * s.width);
        ExtendedModel e = with(m, {id, std::move(q), s.at});
        rmse = fit_extended(e, d, train, 40).rmse;
        const std::vector<bool> free = e.free_mask();
        const auto k = static_cast<double>(std::count(free.begin(), free.end(), true));
        bic = n * std::log(std::max(rmse * rmse, 1e-300)) + k * std::log(n);
        return e;
      };
      double rmse_climbing = 0.0, bic_climbing = 0.0, rmse_topping = 0.0, bic_topping = 0.0;
      std::optional<ExtendedModel> a = fitted(climbing, false, rmse_climbing, bic_climbing);
      std::optional<ExtendedModel> b = fitted(topping, true, rmse_topping, bic_topping);
      const bool tops_out =
          b && (!a || (bic_topping < bic_climbing && rmse_topping < (1.0 - kRicherFormMargin) * rmse_climbing));
      c = tops_out ? std::move(b) : std::move(a);
      if (!c) return std::nullopt;
      break;
    }
    default: return std::nullopt;
  }
  // The fit's parameter block has room for kMaxParams; a model that full
  // takes no more effects.
  if (c->flat().size() > static_cast<std::size_t>(kMaxParams)) return std::nullopt;
  fit_extended(*c, d, train, 40);
  // A periodic torque that settles under 1.5 cycles per revolution is
  // gravity's to name.
  if (id == EffectId::PeriodicTorque && std::abs(c->effects.back().params[1]) > 1.0 / 1.5) return std::nullopt;
  // Fitted outside the physical range the effect table gives it (a negative
  // Stribeck excess, a spring that pushes away, damping that feeds energy
  // in), it is not that effect, whatever it explains.
  try {
    model::effect_from_params(effect_name(id), report_params(c->effects.back(), *c));
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
  return c;
}

}  // namespace

bool repeats_as_detents(double P, double travel) {
  return std::abs(P) <= 1.0 / 1.5 && travel / (2 * kPi * std::abs(P)) >= 2.0;
}

std::vector<ExtendedModel> candidate_forms(EffectId id, const ExtendedModel& m, const fit::FitData& d,
                                           std::span<const std::size_t> train, const std::vector<double>& r) {
  std::vector<ExtendedModel> out;
  if (train.size() < 50) return out;
  if (id == EffectId::Compliance) {
    for (const bool simulated : {false, true})
      if (auto c = compliance_form(m, d, train, simulated)) out.push_back(std::move(*c));
    return out;
  }
  if (auto c = fit_candidate(id, m, d, train, r)) out.push_back(std::move(*c));
  return out;
}

Params report_params(const ActiveEffect& e, const ExtendedModel& m) {
  const auto& q = e.params;
  // A·sin(θ/P + S) as a positive amplitude, a period and a phase (with
  // P < 0 it is A·sin(θ/|P| + π − S)).
  auto periodic = [&](double A, double P, double S) {
    const double phase = std::remainder((P < 0 ? kPi - S : S) + (A < 0 ? kPi : 0.0), 2 * kPi);
    return std::vector<double>{std::abs(A), 2 * kPi * std::abs(P), 1.0 / std::abs(P), phase};
  };
  // In the effect table's order of what discrepancy reports (its names).
  const auto named = [&](const std::vector<double>& v) { return model::reported_values(e.id, v); };
  switch (e.id) {
    case EffectId::Offset: return named({q[0]});
    case EffectId::Gravity: {
      const double phase = std::remainder(q[1] + (q[0] < 0 ? kPi : 0.0), 2 * kPi);
      return named({std::abs(q[0]), phase});
    }
    case EffectId::Spring: return named({q[0], q[1], q[2]});
    case EffectId::PeriodicTorque:
    case EffectId::PositionFriction: return named(periodic(q[0], q[1], q[2]));
    case EffectId::DetentShape: {
      std::vector<double> v{1.0 / base_period(m)};
      for (std::size_t k = 0; k + 2 <= kShapeHarmonics; ++k) {
        v.push_back(std::hypot(q[2 * k], q[2 * k + 1]));
        v.push_back(static_cast<double>(k + 2) / base_period(m));
      }
      v.insert(v.end(), q.begin(), q.end());  // a2, b2, a3, …
      return named(v);
    }
    case EffectId::Stribeck: return named({q[0], std::abs(q[1])});
    case EffectId::NonlinearDamping: return named({q[0], q[1]});
    case EffectId::Drift: return named({q[0], e.setting});
    case EffectId::TimeDelay:
    case EffectId::Saturation:
    case EffectId::Backlash:
    case EffectId::Hysteresis: return named({e.setting});
    case EffectId::Endstop: {
      // A stop that climbs on has no max_torque_Nm.
      Params v = named({e.setting, q[0], q.size() > 1 ? q[1] : std::numeric_limits<double>::quiet_NaN()});
      std::erase_if(v, [](const auto& kv) { return std::isnan(kv.second); });
      return v;
    }
    case EffectId::Compliance: {
      // The ringing against the knob's inertia as this model fits it.
      const double M = std::abs(m.base[model::kM_acc]);
      const double wn = M > 0 ? std::sqrt(e.setting / M) : 0.0;
      return named({e.setting, e.lag_s * e.setting, wn / (2 * kPi), e.lag_s * wn / 2.0});
    }
  }
  return {};
}

namespace {

std::string ordinal(int k) {
  const char* suffix = k % 10 == 1 && k % 100 != 11   ? "st"
                       : k % 10 == 2 && k % 100 != 12 ? "nd"
                       : k % 10 == 3 && k % 100 != 13 ? "rd"
                                                      : "th";
  return std::to_string(k) + suffix;
}

// k when f is within 2 % of k times the base detent frequency, else 0.
int detent_multiple(const ExtendedModel& m, double f) {
  if (!base_has_detents(m)) return 0;
  const double ratio = f * base_period(m);
  const double k = std::round(ratio);
  return k >= 1 && std::abs(ratio - k) < 0.02 * k ? static_cast<int>(k) : 0;
}

// The period over position (SI) of a frequency in the effect table's cycles
// per 2π of travel, and the base detents' period.
double period_of(double cycles_per_rev) { return 2 * kPi / cycles_per_rev; }
double detent_period(const ExtendedModel& m) { return 2 * kPi * base_period(m); }

// "17.3 cycles per revolution (period 20.8°)" | "2.5 mm per cycle": the
// period itself too when the axis presents a frequency.
std::string repeating_at(const fit::AxisUnits& u, double period) {
  return u.cycle.words_with(period) + (u.cycle.frequency ? " (period " + u.position.with(period) + ")" : "");
}

// A sine of the position in rad is once per revolution; in m it is a
// trend over 6 m of travel, which is not gravity: a linear axis's carriage
// weighs the same everywhere (offset). Gravity is no linear candidate
// (implemented_effects(Axis)) unless a caller's own list names it.
Explanation explain_gravity(const fit::AxisUnits& u, double amplitude) {
  if (u.axis == fit::Axis::Linear) {
    return {"over position, as sin(x / 1 m)",
            "The residual follows sin(x / 1 m) with " + u.torque.with(amplitude) +
                " amplitude: gravity's form on a rotary axis; on a linear axis gravity is a constant force "
                "(offset), so this is a slow trend over the travel."};
  }
  return {"over position, once per revolution",
          "The residual repeats once per revolution with " + u.torque.with(amplitude) +
              " amplitude: an unbalanced mass or tilted axis (gravity), or a single detent per revolution."};
}

}  // namespace

Explanation explain(const ActiveEffect& e, const ExtendedModel& m, const Motion& motion) {
  const Params p = report_params(e, m);
  auto v = [&](const char* name) {
    for (const auto& [n, x] : p)
      if (n == name) return x;
    return 0.0;
  };
  const fit::AxisUnits& u = fit::units(motion.axis);
  const std::string effort(u.effort), travel(u.travel), twist(u.twist), rate(u.theta_dot);
  const std::string one_way = "the recording " + std::string(u.moves) + " one way only";
  const auto force = [&](double si) { return u.torque.with(si); };
  switch (e.id) {
    case EffectId::Offset: {
      const std::string weight =
          motion.axis == fit::Axis::Linear ? ", or the weight of a vertical axis's carriage (gravity, on a linear axis)"
                                           : "";
      return {"everywhere", "The " + effort + " sits " + force(v("offset_Nm")) +
                                " off zero at every position and speed: a constant bias (offset), sensor zero or "
                                "preload" + weight + "."};
    }
    case EffectId::Gravity: return explain_gravity(u, v("amplitude_Nm"));
    case EffectId::Spring: {
      const double K3 = v("cubic_Nm_per_rad3");
      const std::string cubic = K3 == 0.0 ? std::string()
                                : K3 > 0  ? ", stiffening by " + u.cubic_stiffness.with(K3) + " (hardening)"
                                          : ", softening by " + u.cubic_stiffness.with(-K3);
      return {"over position, proportional to " + travel,
              "The residual grows with " + travel + ", " + u.stiffness.with(v("stiffness_Nm_per_rad")) + cubic +
                  ", about " + u.position.with(v("centre_rad")) + ": a restoring spring."};
    }
    case EffectId::PeriodicTorque: {
      const int k = detent_multiple(m, v("cycles_per_rev"));
      const std::string relation =
          k > 1 ? "the " + ordinal(k) + " harmonic of the detents at " + u.cycle.with(detent_period(m)) +
                      ", beyond what detent_shape models"
                : std::string("unrelated to the detents");
      return {"over position, " + u.cycle.with(v("period_rad")),
              "A second position-periodic " + effort + " at " + repeating_at(u, v("period_rad")) + ", " +
                  force(v("amplitude_Nm")) + ", " + relation +
                  ": cogging, a second detent track or screw ripple (periodic_torque)."};
    }
    case EffectId::DetentShape: {
      std::string harmonics;
      for (std::size_t k = 2; k <= kShapeHarmonics; ++k) {
        const std::string h = "h" + std::to_string(k);
        harmonics += std::string(k == 2 ? "" : (k == kShapeHarmonics ? " and " : ", ")) +
                     ordinal(static_cast<int>(k)) + " " + force(v((h + "_amplitude_Nm").c_str())) + " at " +
                     u.cycle.with(period_of(v((h + "_cycles_per_rev").c_str())));
      }
      return {"over position, harmonics of the detents at " + u.cycle.with(detent_period(m)),
              "The detents are not sinusoidal: their harmonics are " + harmonics + " (detent_shape)."};
    }
    case EffectId::Stribeck:
      return {"near zero speed (|" + rate + "| below about " + u.speed.with(2 * v("stribeck_velocity_rad_s")) + ")",
              "Friction is " + force(v("static_excess_Nm")) + " above its Coulomb level near zero speed and falls "
              "off over " + u.speed.with(v("stribeck_velocity_rad_s")) + ": Stribeck friction."};
    case EffectId::NonlinearDamping:
      return {"over velocity, not proportional to it",
              "Damping grows as |" + rate + "|^" + format("%.2g", v("exponent")) + ", not linearly: nonlinear damping."};
    case EffectId::PositionFriction:
      return {"over position, sign of velocity, " + u.cycle.with(v("period_rad")),
              "The friction level changes with position, ±" + force(v("depth_Nm")) + " at " +
                  u.cycle.words_with(v("period_rad")) + " (position_friction)."};
    case EffectId::Drift:
      return {"over time", "The friction level changes during the recording by " + force(v("rate_Nm_per_s")) +
                               " per second (drift: warming or wear)."};
    case EffectId::TimeDelay:
      return {"against the motion's derivatives (a lag)",
              "The " + effort + " channel is " + format("%.3g ms %s", std::abs(v("delay_s")) * 1e3,
                                                        v("delay_s") > 0 ? "behind" : "ahead of") +
                  " the motion channels (time_delay)."};
    case EffectId::Saturation:
      return {"at the " + effort + " extremes",
              "The " + effort + " is clipped at ±" + force(v("limit_Nm")) + " (sensor saturation)."};
    case EffectId::Backlash: {
      const double w = v("width_rad");
      if (!motion.reverses) {
        return {motion.span + " (" + one_way + ")",
                "Lost motion of " + u.fine_position.with(w) + " (" + u.position.with(w) +
                    ") between the drive and the detent mechanism (backlash), felt most at " + motion.span + "; " +
                    one_way + "."};
      }
      return {"after reversals", "After every reversal the " + effort + " falls toward zero for " +
                                     u.position.with(w) + " of travel: backlash (lost motion) of " +
                                     u.fine_position.with(w) + " between the drive and the detent mechanism."};
    }
    case EffectId::Hysteresis: {
      // Friction turns over within about three presliding lengths.
      const std::string within = u.fine_position.with(3 * v("presliding_angle_rad"));
      if (!motion.reverses) {
        return {motion.span + " (" + one_way + ")",
                "Friction turns over within about " + within + " instead of jumping (presliding hysteresis, "
                "Dahl), felt most at " + motion.span + "; " + one_way + "."};
      }
      return {"after reversals", "After a reversal friction turns over within about " + within +
                                     " instead of jumping: presliding hysteresis (Dahl)."};
    }
    case EffectId::Endstop: {
      const std::string beyond = "Beyond ±" + u.position.with(v("position_rad")) + " the " + effort + " climbs by " +
                                 u.stiffness.with(v("stiffness_Nm_per_rad"));
      if (e.params.size() > 1)
        return {"at the extremes of the travel",
                beyond + " up to " + force(v("max_torque_Nm")) +
                    " and holds there: a stop that tops out, as a rendered wall does (endstop)."};
      return {"at the extremes of the travel", beyond + ": a hard stop (endstop)."};
    }
    case EffectId::Compliance: {
      // A damping ratio of 1 or more does not ring: the twist follows the
      // torque through its lag c/k, whose corner is k/(2π·c).
      const bool rings = v("zeta") < 1.0;
      const std::string dynamics =
          rings ? format("damping ratio %.2g), ringing near %.3g Hz with the knob's ", v("zeta"), v("frequency_hz")) +
                      std::string(u.mass)
                : format("damping ratio %.2g: %s, no ringing), the ", v("zeta"),
                         v("zeta") > 1.0 ? "overdamped" : "critically damped") +
                      twist + " following the " + effort +
                      format(" with a corner near %.3g Hz",
                             v("stiffness_Nm_per_rad") / (2 * kPi * v("damping_Nm_s_per_rad")));
      const std::string sentence = "The knob lags the motor by the coupling's " + twist + ": " +
                                   u.coupling_stiffness.with(v("stiffness_Nm_per_rad")) + " (" + dynamics +
                                   " (compliance between actuator and knob)";
      if (!motion.reverses)
        return {motion.span + " (" + one_way + ")", sentence + ", felt most at " + motion.span + "; " + one_way + "."};
      return {rings ? "after reversals and breakaways (ringing)" : "after reversals and breakaways",
              sentence + "."};
    }
    default: return {"", std::string(effect_name(e.id)) + "."};
  }
}

}  // namespace knoblab::discovery::detail
