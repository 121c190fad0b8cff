// discover(): base fit, candidate effects scored on held-out blocks, greedy
// selection (see discrepancy.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <numbers>
#include <optional>
#include <cstdio>
#include <span>
#include <string>
#include <utility>

#include "candidates.hpp"
#include "extended_model.hpp"
#include "final_knob.hpp"
#include "forward_view.hpp"
#include "motion.hpp"
#include "knoblab/discovery/block_drop.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/discovery/whiteness.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/model/quantile.hpp"

namespace knoblab::discovery {

namespace {

using detail::ActiveEffect;
using detail::ExtendedModel;

struct Split {
  const fit::FitData* train_data = nullptr;
  const fit::FitData* held_data = nullptr;  // the same recording, or another
  std::vector<std::size_t> train, held;     // rows of train_data / held_data
  std::vector<std::size_t> held_block;  // per held row: its block (0 … B/2 − 1)
  std::size_t held_blocks = 0;
};

// The share of the held-out rows (odd blocks of B) with at least five
// training rows within 1/256 of the position range: 1 for a sweep that
// passes its angles again and again, about 0.3 for one slow revolution.
double position_coverage(const fit::FitData& d, std::size_t B) {
  std::vector<double> train, held;
  for (std::size_t i = 0; i < d.size(); ++i) {
    ((i * B / d.size()) % 2 == 0 ? train : held).push_back(d.theta[i]);
  }
  if (train.size() < 2 || held.empty()) return 1.0;
  std::sort(train.begin(), train.end());
  const double delta = (train.back() - train.front()) / 256.0;
  std::size_t covered = 0;
  for (const double th : held) {
    const auto lo = std::lower_bound(train.begin(), train.end(), th - delta);
    const auto hi = std::upper_bound(train.begin(), train.end(), th + delta);
    covered += hi - lo >= 5 ? 1 : 0;
  }
  return static_cast<double>(covered) / static_cast<double>(held.size());
}

// Time blocks must not hold out angles the training never saw. A recording
// that passes each position once (one slow revolution) held out in 32
// blocks leaves 16 stretches of angle unseen, and its training rows sample
// the angle in a 16-per-range pattern that aliases periodic torques (a
// 28/rev cogging harmonic reads as 12). The blocks are doubled, up to 256
// and at least 16 rows each, until nine in ten held-out rows have training
// rows close by in position.
std::size_t blocks_for(const fit::FitData& d, std::size_t B) {
  while (position_coverage(d, B) < 0.9 && 2 * B <= 256 && d.size() / (2 * B) >= 16) B *= 2;
  return B;
}

// Contiguous time blocks, B of them; even ones train, odd ones are held out.
// With a held-out recording, all of `d` trains and `h`'s B/2 blocks are held
// out. Each side strided evenly down to max_rows.
Split split_rows(const fit::FitData& d, const std::vector<char>& usable_d, const fit::FitData& h,
                 const std::vector<char>& usable_h, std::size_t B, const DiscrepancyOptions& opt) {
  const bool same = &d == &h;
  std::vector<std::size_t> train, held, held_block;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!usable_d[i]) continue;
    const std::size_t b = i * B / d.size();
    if (!same || b % 2 == 0) {
      train.push_back(i);
    } else {
      held.push_back(i);
      held_block.push_back(b / 2);
    }
  }
  for (std::size_t i = 0; !same && i < h.size(); ++i) {
    if (!usable_h[i]) continue;
    held.push_back(i);
    held_block.push_back(i * (B / 2) / h.size());
  }
  Split s;
  s.train_data = &d;
  s.held_data = &h;
  s.held_blocks = B / 2;
  const std::size_t st = std::max<std::size_t>(1, train.size() / opt.max_rows);
  for (std::size_t j = 0; j < train.size(); j += st) s.train.push_back(train[j]);
  const std::size_t sh = std::max<std::size_t>(1, held.size() / opt.max_rows);
  for (std::size_t j = 0; j < held.size(); j += sh) {
    s.held.push_back(held[j]);
    s.held_block.push_back(held_block[j]);
  }
  return s;
}

fit::FitData subset(const fit::FitData& d, const std::vector<std::size_t>& rows) {
  fit::FitData s;
  s.rate_hz = d.rate_hz;
  for (const std::size_t i : rows) {
    s.t.push_back(d.t[i]);
    s.theta.push_back(d.theta[i]);
    s.omega.push_back(d.omega[i]);
    s.alpha.push_back(d.alpha[i]);
    s.torque.push_back(d.torque[i]);
  }
  return s;
}

struct Score {
  double rmse_train = 0.0, rmse_held = 0.0, bic = 0.0;
  std::size_t held_rows = 0;
  std::vector<double> block_mse;
};

std::size_t free_count(const ExtendedModel& m) {
  std::size_t k = 0;
  for (const bool f : m.base_fitted) k += f ? 1 : 0;
  for (const ActiveEffect& e : m.effects)
    if (!e.held) k += detail::parameter_count(e);
  return k;
}

// A model's residuals on the training and held-out rows (NaN where it does
// not describe a row).
struct Residuals {
  std::vector<double> train, held;
  std::size_t free = 0;
};

Residuals residuals_of(const ExtendedModel& m, const Split& s) {
  return {detail::residuals(m, *s.train_data, s.train), detail::residuals(m, *s.held_data, s.held),
          free_count(m)};
}

// Error figures of `r` on the rows it and `other` both describe: two models
// are compared on the same rows (a delay moves some rows' inputs into the
// stick band).
Score score(const Residuals& r, const Residuals& other, const Split& s) {
  const auto both = [](double a, double b) { return !std::isnan(a) && !std::isnan(b); };
  Score out;
  double ss = 0.0, nt = 0.0;
  for (std::size_t j = 0; j < r.train.size(); ++j) {
    if (!both(r.train[j], other.train[j])) continue;
    ss += r.train[j] * r.train[j];
    nt += 1.0;
  }
  if (nt == 0.0) return out;
  out.rmse_train = std::sqrt(ss / nt);
  out.bic = nt * std::log(ss / nt) + static_cast<double>(r.free) * std::log(nt);
  std::vector<double> sum(s.held_blocks, 0.0), cnt(s.held_blocks, 0.0);
  double sh = 0.0, nh = 0.0;
  for (std::size_t j = 0; j < r.held.size(); ++j) {
    if (!both(r.held[j], other.held[j])) continue;
    sh += r.held[j] * r.held[j];
    nh += 1.0;
    sum[s.held_block[j]] += r.held[j] * r.held[j];
    cnt[s.held_block[j]] += 1.0;
  }
  out.rmse_held = nh > 0 ? std::sqrt(sh / nh) : 0.0;
  out.held_rows = static_cast<std::size_t>(nh);
  for (std::size_t b = 0; b < s.held_blocks; ++b) {
    if (cnt[b] > 0) out.block_mse.push_back(sum[b] / cnt[b]);
  }
  return out;
}

Score score(const Residuals& r, const Split& s) { return score(r, r, s); }

// Is the drop there in most held-out blocks (block_drop.hpp)?
double drop_consistency_of(const Score& before, const Score& after) {
  const std::size_t B = std::min(before.block_mse.size(), after.block_mse.size());
  if (B < 2) return 0.0;
  std::vector<double> drop(B);
  for (std::size_t b = 0; b < B; ++b) {
    drop[b] = std::log(std::max(before.block_mse[b], 1e-300) / std::max(after.block_mse[b], 1e-300));
  }
  return drop_consistency(drop);
}

// Where a change of model acts: the held-out rows where it changes the
// model's torque (before − after residual) by at least a tenth of its
// largest change on the training rows (their 99th percentile of |change|).
std::vector<char> support_of(const Residuals& before, const Residuals& after) {
  std::vector<double> change;
  for (std::size_t j = 0; j < before.train.size(); ++j) {
    const double c = before.train[j] - after.train[j];
    if (std::isfinite(c)) change.push_back(std::abs(c));
  }
  std::vector<char> out(before.held.size(), 0);
  if (change.empty()) return out;
  const double threshold = 0.1 * model::quantile(std::move(change), 0.99);
  if (!(threshold > 0)) return out;
  for (std::size_t j = 0; j < before.held.size(); ++j) {
    const double c = before.held[j] - after.held[j];
    out[j] = std::isfinite(c) && std::abs(c) >= threshold;
  }
  return out;
}

// Held-out RMS of `before` and `after` over the rows in `support` both describe.
struct SupportFigures {
  std::size_t rows = 0;
  double before = 0.0, after = 0.0;
  double gain() const { return before > 0 ? 1.0 - after / before : 0.0; }
};
SupportFigures on_support(const Residuals& before, const Residuals& after, const std::vector<char>& support) {
  SupportFigures out;
  double sb = 0.0, sa = 0.0;
  for (std::size_t j = 0; j < support.size(); ++j) {
    if (!support[j] || std::isnan(before.held[j]) || std::isnan(after.held[j])) continue;
    sb += before.held[j] * before.held[j];
    sa += after.held[j] * after.held[j];
    ++out.rows;
  }
  if (out.rows > 0) {
    out.before = std::sqrt(sb / static_cast<double>(out.rows));
    out.after = std::sqrt(sa / static_cast<double>(out.rows));
  }
  return out;
}

// Each finding's before/after figures over the rows the base and every
// finding's model describe (a delay or a twist leaves some out): finding k's
// after is finding k + 1's before. Its sentence ends with the held-out pair.
void chain_figures(std::vector<Finding>& findings, const std::vector<Residuals>& chain, const Split& s,
                   const fit::Unit& torque) {
  Residuals common{std::vector<double>(s.train.size(), 0.0), std::vector<double>(s.held.size(), 0.0), 0};
  for (const Residuals& r : chain) {
    for (std::size_t j = 0; j < r.train.size(); ++j)
      if (std::isnan(r.train[j])) common.train[j] = std::nan("");
    for (std::size_t j = 0; j < r.held.size(); ++j)
      if (std::isnan(r.held[j])) common.held[j] = std::nan("");
  }
  std::vector<Score> on_common;
  for (const Residuals& r : chain) on_common.push_back(score(r, common, s));
  for (std::size_t k = 0; k < findings.size(); ++k) {
    Finding& f = findings[k];
    const Score &before = on_common[k], &after = on_common[k + 1];
    f.rmse_before_Nm = before.rmse_train;
    f.rmse_after_Nm = after.rmse_train;
    f.heldout_rmse_before_Nm = before.rmse_held;
    f.heldout_rmse_after_Nm = after.rmse_held;
    f.bic_before = before.bic;
    f.bic_after = after.bic;
    f.heldout_rows = after.held_rows;
    const SupportFigures where = on_support(chain[k], chain[k + 1], support_of(chain[k], chain[k + 1]));
    f.support_rows = where.rows;
    f.support_heldout_rmse_before_Nm = where.before;
    f.support_heldout_rmse_after_Nm = where.after;
    char buf[200];
    std::snprintf(buf, sizeof buf, " Held-out RMS %.3g → %s", torque(before.rmse_held), torque.with(after.rmse_held).c_str());
    f.explanation += buf;
    if (after.held_rows < s.held.size()) {
      std::snprintf(buf, sizeof buf, ", over the %zu of %zu held-out rows %s", after.held_rows, s.held.size(),
                    findings.size() > 1 ? "every model from the base to the last finding describes"
                                        : "both models describe");
      f.explanation += buf;
    }
    // An effect confined to part of the recording: its figures where it acts too.
    if (where.rows > 0 && 2 * where.rows < after.held_rows) {
      std::snprintf(buf, sizeof buf, "; %.3g → %s on the %zu held-out rows where it acts", torque(where.before),
                    torque.with(where.after).c_str(), where.rows);
      f.explanation += buf;
    }
    f.explanation += ".";
  }
}

Params summary_params(const ExtendedModel& m) {
  Params out;
  for (std::size_t k = 0; k < m.base.size(); ++k) {
    out.emplace_back(std::string(model::kThesisParamNames[k]), m.base[k]);
  }
  std::map<EffectId, int> seen;
  for (const ActiveEffect& e : m.effects) {
    // A second periodic torque is "periodic_torque#2.…".
    const int k = ++seen[e.id];
    const std::string prefix = std::string(effect_name(e.id)) + (k > 1 ? "#" + std::to_string(k) : "");
    for (const auto& [name, value] : detail::report_params(e, m)) {
      out.emplace_back(prefix + "." + name, value);
    }
  }
  return out;
}

ModelSummary summary_of(const ExtendedModel& m, const Score& s) {
  ModelSummary out;
  out.params = summary_params(m);
  out.rmse_Nm = s.rmse_train;
  out.heldout_rmse_Nm = s.rmse_held;
  out.bic = s.bic;
  out.heldout_rows = s.held_rows;
  return out;
}

}  // namespace

std::vector<EffectId> implemented_effects() {
  return {EffectId::Offset,           EffectId::Gravity,    EffectId::Spring,
          EffectId::PeriodicTorque,   EffectId::DetentShape, EffectId::Stribeck,
          EffectId::NonlinearDamping, EffectId::PositionFriction, EffectId::Drift,
          EffectId::TimeDelay,        EffectId::Saturation, EffectId::Backlash,
          EffectId::Hysteresis,       EffectId::Endstop,    EffectId::Compliance};
}

namespace {

// Pearson correlation over the rows where both are finite (0 when either is
// constant there).
double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) continue;
    n += 1, sa += a[i], sb += b[i], saa += a[i] * a[i], sbb += b[i] * b[i], sab += a[i] * b[i];
  }
  if (n < 2) return 0.0;
  const double va = saa - sa * sa / n, vb = sbb - sb * sb / n;
  return va > 0 && vb > 0 ? (sab - sa * sb / n) / std::sqrt(va * vb) : 0.0;
}

// Samples slower than this are held by static friction (or inside the stick
// band): no sliding law describes them, so they are left out.
double slow_speed(const fit::FitData& d, const std::optional<fit::StickBand>& stick) {
  std::vector<double> speed(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) speed[i] = std::abs(d.omega[i]);
  double slow = 0.02 * model::quantile(std::move(speed), 0.95);
  if (stick) slow = std::max(slow, stick->dv);
  return slow;
}

std::vector<char> faster_than(const fit::FitData& d, double slow) {
  std::vector<char> out(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) out[i] = std::abs(d.omega[i]) >= slow;
  return out;
}

// A held-out recording's rows inside the velocity range the training covered
// (its 0.5 … 99.5 % quantiles, widened by a tenth): the model is checked where
// it was fitted, not extrapolated (a fast return move before a slow pass).
std::vector<char> within_training_speeds(const fit::FitData& d, const std::vector<char>& usable_d,
                                         const fit::FitData& h, double slow) {
  std::vector<double> w;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (usable_d[i]) w.push_back(d.omega[i]);
  std::vector<char> out = faster_than(h, slow);
  if (w.empty()) return out;
  std::sort(w.begin(), w.end());
  const double lo = w[static_cast<std::size_t>(0.005 * static_cast<double>(w.size() - 1))];
  const double hi = w[static_cast<std::size_t>(0.995 * static_cast<double>(w.size() - 1))];
  const double pad = 0.1 * (hi - lo);
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double v = h.omega[i];
    // Only the directions the training saw (a slow pass one way says nothing
    // about the other).
    const bool seen = v > 0 ? hi > slow : lo < -slow;
    out[i] = out[i] && seen && v >= lo - pad && v <= hi + pad;
  }
  return out;
}

void append_trace(ResidualTrace& tr, const fit::FitData& d, std::span<const std::size_t> rows,
                  const std::vector<double>& before, const std::vector<double>& after, bool held) {
  for (std::size_t j = 0; j < rows.size(); ++j) {
    // Rows a model does not describe (a delay moved its inputs into the stick
    // band) have no residual to show.
    if (std::isnan(before[j]) || std::isnan(after[j])) continue;
    const std::size_t i = rows[j];
    tr.t.push_back(d.t[i]);
    tr.theta.push_back(d.theta[i]);
    tr.omega.push_back(d.omega[i]);
    tr.torque.push_back(d.torque[i]);
    tr.before.push_back(before[j]);
    tr.after.push_back(after[j]);
    tr.heldout.push_back(held ? 1 : 0);
  }
}

// What outbid the detents in the base's first search: a trend over
// position that the base then goes without. The structure among the pool's
// spring, gravity and end stops that explains it best on the training rows
// (fitted with the base less its detents), and the torque that structure
// alone puts on a row, moving or not: the walls of a rendered knob (120
// mN·m against 10 mN·m detents) outbid its detents at every frequency their
// steps reach, so the detents are searched for with it taken out, and only
// where it does not act when that leaves enough rows.
class Trend {
 public:
  explicit Trend(ExtendedModel with) : with_(std::move(with)) {
    ExtendedModel without = with_;
    without.effects.pop_back();
    with_layout_ = detail::layout_of(with_), without_layout_ = detail::layout_of(without);
    with_params_ = with_.flat(), without_params_ = without.flat();
  }
  // The structure's torque on row i of d: the model with it less the same
  // model (its base as fitted with it) without it.
  double torque(const fit::FitData& d, std::size_t i) const {
    const auto base = model::ThesisModel<double>::from_params(with_params_.data());
    detail::RowInputs in;
    in.theta = d.theta[i];
    in.omega = d.omega[i];
    in.alpha = d.alpha[i];
    return detail::extended_torque(with_layout_, with_params_.data(), base, in) -
           detail::extended_torque(without_layout_, without_params_.data(), base, in);
  }
  // d with the structure's torque taken out of every row's.
  fit::FitData taken_out_of(const fit::FitData& d) const {
    fit::FitData out = d;
    for (std::size_t i = 0; i < d.size(); ++i) out.torque[i] -= torque(d, i);
    return out;
  }

 private:
  ExtendedModel with_;
  detail::Layout with_layout_, without_layout_;
  std::vector<double> with_params_, without_params_;
};

std::optional<Trend> trend_of(const fit::FitResult& f, const fit::FitData& d, std::span<const std::size_t> train,
                              const std::vector<EffectId>& pool, double slow) {
  ExtendedModel m;
  m.base = f.params;
  m.base_fitted = f.fitted;
  for (const std::size_t k : {model::kA_pos, model::kP_pos, model::kS_pos}) m.base_fitted[k] = false;
  m.base[model::kA_pos] = 0.0;
  m.stick_speed = slow;
  detail::fit_extended(m, d, train);
  std::vector<double> r = detail::residuals(m, d, train);
  for (double& v : r) v = std::isnan(v) ? 0.0 : v;
  std::optional<Trend> best;
  double best_rmse = 0.0;
  for (const EffectId id : {EffectId::Spring, EffectId::Gravity, EffectId::Endstop}) {
    if (std::find(pool.begin(), pool.end(), id) == pool.end()) continue;
    for (ExtendedModel& c : detail::candidate_forms(id, m, d, train, r)) {
      double ss = 0.0, n = 0.0;
      for (const double v : detail::residuals(c, d, train))
        if (!std::isnan(v)) ss += v * v, n += 1.0;
      if (!(n > 0.0)) continue;
      const double rmse = std::sqrt(ss / n);
      if (best && !(rmse < best_rmse)) continue;
      best.emplace(std::move(c));
      best_rmse = rmse;
    }
  }
  return best;
}

DiscrepancyResult run(const fit::FitData& d, const fit::FitData& h, const DiscrepancyOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  if (d.size() < 200 || h.size() < 200) throw fit::FitDataError("too few samples for discrepancy discovery");
  DiscrepancyResult out;
  out.axis = d.axis;
  out.heldout_recording = &d != &h;
  out.min_reported_gain = opt.min_reported_gain;

  // Base model on the training blocks, as the characterization fits it: its
  // detent search, its stick band (inside which the sliding law does not
  // hold, so those samples are left out of the discovery too).
  const std::vector<char> all_d(d.size(), 1), all_h(h.size(), 1);
  // One block count for both splits below, so that the base is never fitted
  // on rows the second split holds out.
  const std::size_t B0 = std::max<std::size_t>(4, opt.blocks);
  const std::size_t B = out.heldout_recording ? B0 : blocks_for(d, B0);
  out.blocks = out.heldout_recording ? 0 : B;
  Split s = split_rows(d, all_d, h, all_h, B, opt);
  const auto [lo, hi] = std::minmax_element(d.theta.begin(), d.theta.end());
  std::optional<fit::StickBand> stick;  // the base's Eq. 7 band, carried to the final knob
  const std::vector<EffectId> pool = opt.effects.empty() ? implemented_effects(d.axis) : opt.effects;
  ExtendedModel m;
  double slow = 0.0;
  // A trend that outbid the detents, and the detents then found without it
  // (only where it does not act: detents_between).
  std::optional<Trend> trend;
  bool detents_between = false;
  if (opt.base_model) {
    // The given model's terms, held as given (or refitted from them).
    m = detail::extended_of(*opt.base_model);
    stick = opt.base_model->stick;
    if (!opt.refit_base) {
      m.base_fitted.assign(m.base.size(), false);
      if (opt.base_model->detent_phase_unknown && opt.base_model->detents) m.base_fitted[model::kS_pos] = true;
      for (ActiveEffect& e : m.effects) e.held = true;
    }
    slow = slow_speed(d, stick);
  } else {
    opt.hooks.report("fitting the base model");
    fit::FitOptions base_options;
    base_options.hooks = opt.hooks;
    fit::FitResult base_fit = fit::fit_knob(subset(d, s.train), base_options);
    // A "detent" term under 1.5 cycles per revolution, or with fewer than two
    // periods inside the swept range, is a slow trend over position, not
    // detents: the base goes without it, and gravity or a spring must earn it
    // back on held-out data under their own names. The knob's real detents,
    // which the trend outbid, are searched for again above it.
    const double range = *hi - *lo;
    const auto slow_trend = [&](const fit::FitResult& f) {
      return f.fitted[model::kA_pos] && !detail::repeats_as_detents(f.params[model::kP_pos], range);
    };
    if (slow_trend(base_fit)) {
      fit::FitOptions above = base_options;
      above.min_detents_per_rev = std::max(1.5, 2.0 * 2 * std::numbers::pi / std::max(range, 1e-9)) * 1.01;
      if (above.min_detents_per_rev < above.max_detents_per_rev) {
        std::vector<std::size_t> rows = s.train;
        trend = trend_of(base_fit, d, s.train, pool, slow_speed(d, base_fit.stick));
        if (trend) {
          // Where the structure does not act (under a tenth of its largest
          // torque), when that is a quarter of the rows or more: end stops
          // leave the travel between them; a spring or gravity acts
          // everywhere.
          std::vector<double> size;
          for (const std::size_t i : s.train) size.push_back(std::abs(trend->torque(d, i)));
          const double peak = model::quantile(size, 0.99);
          std::vector<std::size_t> quiet;
          for (std::size_t j = 0; j < s.train.size(); ++j)
            if (size[j] <= 0.1 * peak) quiet.push_back(s.train[j]);
          if (quiet.size() >= s.train.size() / 4 && quiet.size() < s.train.size()) {
            rows = std::move(quiet);
            detents_between = true;
          }
        }
        fit::FitResult again = fit::fit_knob(subset(trend ? trend->taken_out_of(d) : d, rows), above);
        if (!slow_trend(again)) base_fit = std::move(again);
      }
    }
    stick = base_fit.stick;
    // Near-stuck samples: inside the fitted stick band, and in any case below
    // 2 % of the brisk speed (an effect the base lacks can hide the band from
    // its estimate).
    slow = slow_speed(d, stick);
    m.base = base_fit.params;
    m.base_fitted = base_fit.fitted;
    if (stick) {
      m.stick_band = stick->dv;
      // One breakaway level both ways: behind a play the band's estimate is
      // unreliable in one direction (the mechanism stands while the knob
      // crosses the play), so the larger one stands for both.
      m.breakaway = std::max(stick->D_pos, stick->D_neg);
    }
    if (slow_trend(base_fit)) {
      for (const std::size_t k : {model::kA_pos, model::kP_pos, model::kS_pos}) m.base_fitted[k] = false;
      m.base[model::kA_pos] = 0.0;
      trend.reset();  // no detents found without it either
      detents_between = false;
    } else if (detents_between) {
      // The detents as the search found them where the trend does not act,
      // held: Eq. 6's detent term runs on over the whole travel, and fitted
      // over the rows where the trend acts (a rendered knob's walls, where
      // its detents end) it would be pulled off the detents.
      for (const std::size_t k : {model::kA_pos, model::kP_pos, model::kS_pos}) m.base_fitted[k] = false;
    }
  }
  out.base_given = opt.base_model.has_value();
  out.base_held = out.base_given && !opt.refit_base;
  m.stick_speed = slow;
  const std::vector<char> usable_d = faster_than(d, slow);
  s = split_rows(d, usable_d, h,
                 out.heldout_recording ? within_training_speeds(d, usable_d, h, slow) : usable_d, B, opt);
  if (s.held.size() < 100) {
    throw fit::FitDataError(out.heldout_recording
                                ? "the held-out recording has " + std::to_string(s.held.size()) +
                                      " rows inside the training's velocity range; it needs 100"
                                : "too few moving samples for held-out blocks");
  }
  // The base is refined per sample as the detents were found: with the
  // trend taken out, which it still goes without (a term it lacks would
  // otherwise pull its detents' period towards the trend's steps).
  detail::fit_extended(m, trend ? trend->taken_out_of(d) : d, s.train);
  opt.hooks.check();
  const ExtendedModel base_model = m;
  const Residuals base_res = residuals_of(m, s);
  const Score base_score = score(base_res, s);
  Residuals current_res = base_res;
  Score current = base_score;
  out.base = summary_of(m, current);
  out.train_rows = s.train.size();
  out.heldout_rows = s.held.size();
  out.slow_speed = slow;

  // The base, then the model after each finding: their error figures chain.
  std::vector<Residuals> chain{base_res};
  // Only a recording that reverses may be said to (the findings' sentences):
  // one that turns back by more than 1 % of its range.
  const bool reverses = detail::count_reversals(d.theta, 0.01 * (*hi - *lo)) > 0;

  for (int round = 0; out.findings.size() < opt.max_findings; ++round) {
    // Rows the model does not describe add nothing to a candidate's start.
    std::vector<double> r_train = current_res.train;
    for (double& v : r_train) v = std::isnan(v) ? 0.0 : v;
    struct Tried {
      ExtendedModel model;
      Score score, before;  // the candidate, and the current model on the same rows
      double gain = 0.0, t = 0.0;
      std::vector<double> added;  // the torque it adds on the training rows (NaN: undescribed)
      SupportFigures where;       // held-out, where it acts
    };
    // What the selection below asks of a term (and of one form over
    // another): at least min_heldout_gain, or min_reported_gain where it
    // acts, consistent over the held-out blocks (drop_consistency ≥ min_t)
    // and a lower BIC.
    const auto significant = [&](const Tried& c) {
      const bool local = c.where.rows >= opt.min_support_rows && c.where.gain() >= opt.min_reported_gain;
      return (c.gain >= opt.min_heldout_gain || local) && c.t >= opt.min_t && c.score.bic < c.before.bic;
    };
    // Of an effect's forms, the one the held-out rows favour as they favour
    // one effect over another: a significant one over one that is not, then
    // the larger gain; of two that are not, the more consistent drop.
    const auto favoured = [&](const Tried& a, const Tried& b) {
      if (significant(a) != significant(b)) return significant(a);
      return significant(a) ? a.gain > b.gain : a.t > b.t;
    };
    std::vector<Tried> tried;
    const std::string stage = "trying candidates, round " + std::to_string(round + 1);
    for (std::size_t k = 0; k < pool.size(); ++k) {
      const EffectId id = pool[k];
      opt.hooks.report(stage, k, pool.size());
      // Periodic torques may repeat (cogging has several); the rest are one each.
      if (m.has(id) && id != EffectId::PeriodicTorque) continue;
      std::vector<ExtendedModel> forms = detail::candidate_forms(id, m, d, s.train, r_train);
      opt.hooks.check();
      std::optional<Tried> best_form;
      for (ExtendedModel& form : forms) {
        Tried t{std::move(form), {}, {}, 0.0, 0.0, {}, {}};
        const Residuals r = residuals_of(t.model, s);
        t.added.resize(r.train.size());
        for (std::size_t j = 0; j < r.train.size(); ++j) t.added[j] = current_res.train[j] - r.train[j];
        t.where = on_support(current_res, r, support_of(current_res, r));
        t.score = score(r, current_res, s);
        t.before = score(current_res, r, s);
        t.gain = t.before.rmse_held > 0 ? 1.0 - t.score.rmse_held / t.before.rmse_held : 0.0;
        t.t = drop_consistency_of(t.before, t.score);
        if (!best_form || favoured(t, *best_form)) best_form = std::move(t);
      }
      if (!best_form) continue;
      out.candidates.push_back({round, id, best_form->gain, best_form->t, false});
      tried.push_back(std::move(*best_form));
    }
    if (tried.empty()) break;
    std::sort(tried.begin(), tried.end(), [](const Tried& a, const Tried& b) { return a.gain > b.gain; });
    // The largest held-out gain among the significant candidates decides: at
    // least min_heldout_gain, consistent over the held-out blocks
    // (drop_consistency ≥ min_t) and a lower BIC. A larger gain that is not consistent (a few blocks'
    // breakaway transients, which a spurious delay absorbs) is no evidence of
    // a term, so it does not veto one that improves every block; it only
    // lowers the chosen one's confidence (the runner-up below).
    // Judged over all held-out rows, or where it acts when that is a part.
    auto chosen = std::find_if(tried.begin(), tried.end(), significant);
    if (chosen == tried.end()) break;
    // Parsimony: of the significant candidates explaining the same residual,
    // the one with the fewest parameters, unless a richer one is better on
    // held-out data by the stated margin.
    const auto same_residual = [](const Tried& a, const Tried& b) {
      return correlation(a.added, b.added) >= 0.5;
    };
    const auto margin_over = [](const Tried& rich, const Tried& simple) {  // held-out RMS, relative
      return 1.0 - (1.0 - rich.gain) / (1.0 - simple.gain);
    };
    const Tried* rival = nullptr;  // the chosen's runner-up on the same residual
    for (auto c = tried.begin(); c != tried.end(); ++c) {
      if (c == chosen || !significant(*c) || !same_residual(*c, *chosen)) continue;
      const std::size_t nc = detail::parameter_count(c->model.effects.back());
      const std::size_t nb = detail::parameter_count(chosen->model.effects.back());
      if (nc < nb && margin_over(*chosen, *c) < opt.parsimony_margin) chosen = c;
    }
    for (auto c = tried.begin(); c != tried.end(); ++c) {
      if (c == chosen || !significant(*c) || !same_residual(*c, *chosen)) continue;
      if (!rival || c->gain > rival->gain) rival = &*c;
    }
    std::string runner_up;
    if (rival) {
      const ActiveEffect& re = rival->model.effects.back();
      const std::size_t nr = detail::parameter_count(re);
      const std::size_t nc = detail::parameter_count(chosen->model.effects.back());
      const double better = margin_over(*chosen, *rival);  // > 0: the chosen is better
      // Relative, as the selection compares them (each candidate against the
      // current model on the rows both describe).
      const double rival_over_ours = (1.0 - rival->gain) / (1.0 - chosen->gain) - 1.0;
      char buf[320];
      if (nr > nc && better < 0) {
        std::snprintf(buf, sizeof buf,
                      " Preferred to %s (%zu parameters against %zu), whose held-out RMS is %.1f %% lower, under the "
                      "%.0f %% a richer name must win by.",
                      std::string(effect_name(re.id)).c_str(), nr, nc, -100.0 * better, 100.0 * opt.parsimony_margin);
      } else {
        char how[64];
        if (rival_over_ours >= 1.0) std::snprintf(how, sizeof how, "%.3g times as high", 1.0 + rival_over_ours);
        else std::snprintf(how, sizeof how, "%.1f %% %s", 100.0 * std::abs(rival_over_ours),
                           rival_over_ours >= 0 ? "higher" : "lower");
        std::snprintf(buf, sizeof buf, " Runner-up: %s (%zu parameters), held-out RMS %s.",
                      std::string(effect_name(re.id)).c_str(), nr, how);
      }
      runner_up = buf;
    }
    std::rotate(tried.begin(), chosen, chosen + 1);  // chosen first, the rest by gain
    const Tried& best = tried.front();
    const ActiveEffect& added = best.model.effects.back();
    for (CandidateScore& c : out.candidates)
      if (c.round == round && c.effect == added.id) c.kept = true;

    Finding f;
    f.effect = added.id;
    f.params = detail::report_params(added, best.model);
    f.t_stat = best.t;  // the error figures: chained below, once every finding is known
    // Confidence: how consistent the held-out gain is (t), and how clearly
    // this effect beat the runner-up (another effect explaining the same
    // residual nearly as well makes the name less certain).
    const double next_gain = tried.size() > 1 ? std::max(0.0, tried[1].gain) : 0.0;
    const double margin = std::clamp(1.0 - next_gain / best.gain, 0.0, 1.0);
    const double consistency = 1.0 - std::exp(-best.t / 4.0);
    f.confidence = std::clamp(consistency * (0.5 + 0.5 * margin), 0.0, 1.0);
    m = best.model;
    const Residuals before = std::exchange(current_res, residuals_of(m, s));
    current = score(current_res, s);
    chain.push_back(current_res);

    const detail::Explanation ex =
        detail::explain(added, m, {reverses, detail::effect_span(d, s.train, before.train, current_res.train), d.axis});
    f.where = ex.where;
    f.explanation = ex.sentence + runner_up;
    out.findings.push_back(std::move(f));
  }
  chain_figures(out.findings, chain, s, fit::units(d.axis).torque);
  // Below the reporting bar the terms found stay tentative and the final
  // model is the base (one-line rule: discrepancy.hpp, min_reported_gain).
  // The bar is applied where the findings act: on the held-out rows in any
  // finding's support, base → final.
  std::vector<char> acts(s.held.size(), 0);
  for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
    const std::vector<char> one = support_of(chain[k], chain[k + 1]);
    for (std::size_t j = 0; j < acts.size(); ++j) acts[j] = acts[j] || one[j];
  }
  const SupportFigures together = on_support(chain.front(), chain.back(), acts);
  const bool over_all = current.rmse_held <= (1.0 - opt.min_reported_gain) * out.base.heldout_rmse_Nm;
  if (!out.findings.empty() && together.gain() < opt.min_reported_gain && !over_all) {
    out.tentative = std::move(out.findings);
    out.tentative_heldout_rmse_Nm = current.rmse_held;
    out.findings.clear();
    for (CandidateScore& c : out.candidates) c.kept = false;
    m = base_model;
    current_res = base_res;
    current = base_score;
  }
  out.final_model = summary_of(m, current);
  out.final_knob = detail::final_knob_of(m, stick);
  if (out.findings.empty()) {
    out.same_rows = {out.base.heldout_rows, std::nan(""), std::nan("")};
  } else {
    const Score b = score(base_res, current_res, s);
    out.same_rows = {b.held_rows, b.rmse_held, score(current_res, base_res, s).rmse_held};
  }
  opt.hooks.report("residual tests");
  append_trace(out.trace, d, s.train, base_res.train, current_res.train, false);
  append_trace(out.trace, h, s.held, base_res.held, current_res.held, true);
  // The forward view on the held-out rows, windows begun in time order.
  for (auto [summary, model] : {std::pair{&out.base, &base_model}, std::pair{&out.final_model, static_cast<const ExtendedModel*>(&m)}}) {
    const detail::ForwardError fe = detail::forward_error(*model, h, s.held);
    summary->forward_rmse_rad = fe.windows > 0 ? fe.rms_theta_rad : std::nan("");
  }
  for (auto [summary, residual] : {std::pair{&out.base, &out.trace.before},
                                   std::pair{&out.final_model, &out.trace.after}}) {
    const ResidualFigures f = residual_figures(out.trace, *residual);
    summary->fit_percent = f.fit_percent;
    summary->whiteness_p = f.whiteness.p;
    summary->independence_p = f.independence.p;
  }
  opt.hooks.check();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace

DiscrepancyResult discover(const fit::FitData& d, const DiscrepancyOptions& opt) {
  return run(d, d, opt);
}

DiscrepancyResult discover(const fit::FitData& d, const fit::FitData& heldout,
                           const DiscrepancyOptions& opt) {
  return run(d, heldout, opt);
}

}  // namespace knoblab::discovery
