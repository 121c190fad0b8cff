#include "extended_model.hpp"

#include "coupled_knob.hpp"
#include "knoblab/model/filters.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace knoblab::discovery::detail {

bool ExtendedModel::has(EffectId id) const { return find(id) != nullptr; }

bool ExtendedModel::has_detents() const {
  const bool fitted = base_fitted.size() > model::kA_pos ? base_fitted[model::kA_pos] : true;
  return fitted || (base.size() > model::kA_pos && base[model::kA_pos] != 0.0);
}

const ActiveEffect* ExtendedModel::find(EffectId id) const {
  for (const ActiveEffect& e : effects)
    if (e.id == id) return &e;
  return nullptr;
}

std::vector<double> ExtendedModel::flat() const {
  std::vector<double> p = base;
  for (const ActiveEffect& e : effects) p.insert(p.end(), e.params.begin(), e.params.end());
  return p;
}

bool ExtendedModel::simulates_coupling() const {
  for (const ActiveEffect& e : effects)
    if (e.id == EffectId::Compliance && e.simulated) return true;
  return false;
}

std::vector<bool> ExtendedModel::free_mask() const {
  // Behind a simulated coupling the knob's own terms stay as the base fit
  // has them: the fit sees only the rows where the knob slides, and terms
  // bent to those would mislead the simulation everywhere else.
  std::vector<bool> free = simulates_coupling() && !refit_behind_coupling ? std::vector<bool>{} : base_fitted;
  free.resize(base.size(), false);
  for (const ActiveEffect& e : effects)
    for (std::size_t k = 0; k < e.params.size(); ++k) free.push_back(e.fitted(k));
  return free;
}

void ExtendedModel::unflatten(std::span<const double> p) {
  std::size_t k = 0;
  for (double& v : base) v = p[k++];
  for (ActiveEffect& e : effects)
    for (double& v : e.params) v = p[k++];
}

Layout layout_of(const ExtendedModel& m) {
  Layout L;
  int at = static_cast<int>(m.base.size());
  for (const ActiveEffect& e : m.effects) {
    L.effects.push_back({e.id, std::vector<double>(e.params.size(), 0.0), e.setting});
    L.offset.push_back(at);
    at += static_cast<int>(e.params.size());
  }
  L.base_detents = m.has_detents();
  if (const ActiveEffect* d = m.find(EffectId::Drift)) L.t_mid = d->setting;
  return L;
}

namespace {

double offset_of(const ExtendedModel& m) {
  const ActiveEffect* o = m.find(EffectId::Offset);
  return o && !o->params.empty() ? o->params[0] : 0.0;
}

// The knob simulated behind the coupling (coupled_knob.hpp) when the model
// has a compliance in its simulated form; nothing otherwise. The knob's
// torques are the model's as it stands.
std::optional<CoupledMotion> coupled_motion(const fit::FitData& d, const ExtendedModel& m) {
  const ActiveEffect* compliance = m.find(EffectId::Compliance);
  if (!compliance || !compliance->simulated) return std::nullopt;
  const double J = std::abs(m.base[model::kM_acc]);
  if (!(J > 0.0) || !(compliance->setting > 0.0)) return std::nullopt;
  const Layout L = layout_of(m);
  const std::vector<double> p = m.flat();
  const auto base = model::ThesisModel<double>::from_params(p.data());
  const double offset = offset_of(m);
  KnobDynamics knob;
  knob.inertia = J;
  const double kinetic = std::max(std::abs(m.base[model::kC_vel_pos]), std::abs(m.base[model::kC_vel_neg]));
  knob.breakaway = std::max(m.breakaway, kinetic);
  knob.torque = [&](double theta, double omega) {
    RowInputs r;
    r.theta = theta;
    r.omega = omega;
    return extended_torque(L, p.data(), base, r) - offset;
  };
  return simulate_coupled_knob(d.t, d.theta, d.omega, {compliance->setting, compliance->lag_s}, knob);
}

// The simulated coupling torque as the recording's went through the
// preparation's low-pass (FitData::torque_lowpass), and which rows are
// within the filter's settling of the knob sticking or breaking away: there
// the simulated ring is compared through the filter, not the knob's law.
struct FilteredCoupling {
  std::vector<double> torque;
  std::vector<char> settled;
};

FilteredCoupling filtered(const fit::FitData& d, const CoupledMotion& c) {
  const std::size_t n = d.size();
  const fit::FitData::Lowpass& lp = d.torque_lowpass;
  FilteredCoupling out;
  out.torque = lp.order > 0 ? model::sosfiltfilt(model::design_cheby2_lowpass(lp.order, lp.stop_atten_db,
                                                                             lp.edge_hz, d.rate_hz),
                                                 c.torque)
                            : c.torque;
  const auto reach = static_cast<std::ptrdiff_t>(lp.order > 0 ? std::ceil(2.0 * d.rate_hz / lp.edge_hz) : 1.0);
  const auto last = static_cast<std::ptrdiff_t>(n) - 1;
  out.settled.assign(n, 1);
  for (std::size_t i = 1; i < n; ++i) {
    if (c.stuck[i] == c.stuck[i - 1]) continue;
    const auto at = static_cast<std::ptrdiff_t>(i);
    for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(0, at - reach); j <= std::min(last, at + reach); ++j)
      out.settled[static_cast<std::size_t>(j)] = 0;
  }
  return out;
}

}  // namespace

// A fraction of the stick speed (2 % of the brisk speed): the encoder's
// motion can be that slow at a reversal with the knob still sliding, but a
// knob whose twist-corrected speed stays under it stands.
constexpr double kStandingFraction = 0.3;

std::vector<RowInputs> row_inputs(const fit::FitData& d, std::span<const std::size_t> rows,
                                  const ExtendedModel& m) {
  const std::size_t n = d.size();
  // Delay: the torque channel lags the motion by δ, so the model at time t
  // sees the motion at t − δ (linear interpolation; clamped at the ends).
  const ActiveEffect* delay = m.find(EffectId::TimeDelay);
  const double shift = delay ? delay->setting * d.rate_hz : 0.0;  // samples
  // Compliance: the encoder is on the motor; the knob lags it by the
  // coupling's twist e, which the measured torque sets through the coupling's
  // spring and damper, k·e + c·ė = τ: a first-order lag of τ/k with time
  // constant c/k (exact for a torque held over each sample). The knob's angle
  // and speed are the motor's less e and ė. α too when it is the encoder's
  // derivative; an accelerometer already rides on the knob side.
  const ActiveEffect* compliance = m.find(EffectId::Compliance);
  std::vector<double> twist, twist_rate, twist_acc, wound;
  const std::optional<CoupledMotion> coupled = coupled_motion(d, m);
  const FilteredCoupling coupled_reading = coupled ? filtered(d, *coupled) : FilteredCoupling{};
  const double offset = offset_of(m);
  if (compliance && !coupled) {
    const double k = compliance->setting, lag = compliance->lag_s;
    twist.resize(n);
    double e = d.torque[0] / k;
    for (std::size_t i = 0; i < n; ++i) {
      const double target = d.torque[i] / k;
      e = lag > 0.0 && i > 0 ? target + (e - target) * std::exp(-(d.t[i] - d.t[i - 1]) / lag) : target;
      twist[i] = e;
    }
    twist_rate = model::derivative(d.t, twist);
    if (d.alpha_from_encoder) twist_acc = model::derivative(d.t, twist_rate);
    // While the knob stands the motor winds the coupling: from the run's
    // first sample s on, the torque is
    //   τ(s) + k·(θ_m − θ_m(s)) + c·(ω_m − ω_m(s)),
    // a prediction from the motor's motion alone that a rigid model, sliding
    // there by the encoder, cannot make. Between standing and the stick
    // speed the knob creeps: neither prediction holds, the row is not
    // described.
    const double still = std::max(m.stick_band, kStandingFraction * m.stick_speed);
    wound.assign(n, std::numeric_limits<double>::quiet_NaN());
    std::size_t s = 0;
    bool standing = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (std::abs(d.omega[i] - twist_rate[i]) >= still) {
        standing = false;
        continue;
      }
      if (!standing) s = i, standing = true;
      wound[i] = d.torque[s] + k * (d.theta[i] - d.theta[s]) + lag * k * (d.omega[i] - d.omega[s]);
    }
  }
  auto at = [&](const std::vector<double>& v, std::size_t i) {
    return shift == 0.0 ? v[i] : value_at(v, static_cast<double>(i) - shift);
  };

  // Operators with memory run over every sample in time order.
  std::vector<double> knob_shift, z;
  std::vector<char> contact;
  if (const ActiveEffect* b = m.find(EffectId::Backlash)) {
    model::Backlash play;
    play.width = b->setting;
    play.reset(d.theta[0]);
    knob_shift.resize(n);
    contact.resize(n);
    // The mechanism behind the play runs ahead of the drive where its
    // position torques pull harder than its friction holds, at the speed
    // where the pull and kinetic friction balance, until the far face stops
    // it (as sim::Plant's massless mechanism does): a detent's downslope
    // snaps it across the play. Standing (slower than the stick band), it is
    // held up to the static level. Position torques and friction from the
    // model as it stands.
    const Layout L = layout_of(m);
    const std::vector<double> p = m.flat();
    const auto base = model::ThesisModel<double>::from_params(p.data());
    const auto& f = m.base;
    const auto free_speed = [&](double phi, bool standing) {
      RowInputs at_rest;
      at_rest.theta = phi;
      const double pull = -extended_torque(L, p.data(), base, at_rest);
      const bool fwd = pull > 0.0;
      const double kinetic = std::abs(fwd ? f[model::kC_vel_pos] : f[model::kC_vel_neg]);
      const double hold = standing ? std::max(m.breakaway, kinetic) : kinetic;
      const double damping = std::abs(fwd ? f[model::kB_vel_pos] : f[model::kB_vel_neg]);
      const double excess = std::abs(pull) - hold;
      if (!(excess > 0.0)) return 0.0;
      const double v = damping > 0.0 ? excess / damping : 1e3;
      return fwd ? v : -v;
    };
    bool standing = true;
    for (std::size_t i = 0; i < n; ++i) {
      const double before = play.knob, dt = i > 0 ? d.t[i] - d.t[i - 1] : 0.0;
      if (i > 0) play.knob += dt * free_speed(play.knob, standing);
      knob_shift[i] = play.update(d.theta[i]) - d.theta[i];
      contact[i] = play.contact ? 1 : 0;
      if (dt > 0.0) standing = std::abs(play.knob - before) < m.stick_band * dt;
    }
  }
  if (const ActiveEffect* h = m.find(EffectId::Hysteresis)) {
    model::DahlFriction dahl;
    dahl.presliding = h->setting;
    dahl.reset(d.omega[0] > 0 ? 1.0 : d.omega[0] < 0 ? -1.0 : 0.0);
    z.resize(n);
    z[0] = dahl.z;
    for (std::size_t i = 1; i < n; ++i) z[i] = dahl.update(d.theta[i] - d.theta[i - 1]);
  }

  std::vector<RowInputs> out;
  out.reserve(rows.size());
  for (const std::size_t i : rows) {
    RowInputs r;
    r.t = d.t[i];
    r.theta = at(d.theta, i);
    r.omega = at(d.omega, i);
    r.alpha = at(d.alpha, i);
    if (coupled) {
      // The simulated knob's motion (α the accelerometer's when it rides on
      // the knob); where it stands or has just stuck or broken away, the
      // coupling's torque through the filter is the prediction.
      r.theta = coupled->theta[i];
      r.omega = coupled->omega[i];
      if (d.alpha_from_encoder) r.alpha = coupled->alpha[i];
      const bool sliding = !coupled->stuck[i] && coupled_reading.settled[i];
      if (!sliding) r.wound = coupled_reading.torque[i] + offset;
      r.described = sliding && std::abs(r.omega) >= m.stick_speed;
      out.push_back(r);
      continue;
    }
    if (compliance) {
      r.theta -= twist[i];
      r.omega -= twist_rate[i];
      if (!twist_acc.empty()) r.alpha -= twist_acc[i];
      r.wound = wound[i];
    }
    if (!knob_shift.empty()) r.theta_shift = knob_shift[i], r.contact = contact[i] != 0;
    if (!z.empty()) r.z = z[i];
    r.described = std::abs(r.omega) >= m.stick_speed;
    out.push_back(r);
  }
  return out;
}

namespace {

constexpr std::size_t kChunk = 256;

struct ChunkCost {
  const Layout* layout;
  std::span<const RowInputs> rows;
  std::span<const double> torque;
  template <typename T>
  bool operator()(const T* p, T* residual) const {
    using std::abs;
    using std::isfinite;  // and ceres::isfinite, ceres::abs for Jets, by ADL
    const auto base = model::ThesisModel<T>::from_params(p);
    for (std::size_t j = 0; j < rows.size(); ++j) {
      if (!rows[j].described) {
        residual[j] = T(0);
        continue;
      }
      residual[j] = extended_torque(*layout, p, base, rows[j]) - T(torque[j]);
      // A trial step that overflows (a power law's exponent, a runaway
      // operator), or whose squares would, is refused quietly; Ceres
      // shrinks the step.
      if (!isfinite(residual[j]) || abs(residual[j]) > T(1e100)) return false;
    }
    return true;
  }
};

}  // namespace

FitReport fit_extended(ExtendedModel& m, const fit::FitData& d, std::span<const std::size_t> rows,
                       int max_iterations) {
  std::vector<double> p = m.flat();
  if (p.size() > static_cast<std::size_t>(kMaxParams))
    throw std::invalid_argument("discrepancy: too many effect parameters in one model");
  const std::size_t used = p.size();
  p.resize(kMaxParams, 0.0);
  const Layout L = layout_of(m);
  const std::vector<RowInputs> in = row_inputs(d, rows, m);
  std::vector<double> torque(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) torque[j] = d.torque[rows[j]];

  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  for (std::size_t s = 0; s < in.size(); s += kChunk) {
    const std::size_t len = std::min(kChunk, in.size() - s);
    auto* cost = new ceres::AutoDiffCostFunction<ChunkCost, ceres::DYNAMIC, kMaxParams>(
        new ChunkCost{&L, std::span(in).subspan(s, len), std::span<const double>(torque).subspan(s, len)},
        static_cast<int>(len));
    problem.AddResidualBlock(cost, nullptr, p.data());
  }
  const std::vector<bool> free = m.free_mask();
  std::vector<int> held;
  for (std::size_t k = 0; k < static_cast<std::size_t>(kMaxParams); ++k)
    if (k >= used || !free[k]) held.push_back(static_cast<int>(k));
  if (held.size() == static_cast<std::size_t>(kMaxParams)) {
    problem.SetParameterBlockConstant(p.data());  // a given model, held whole: nothing to fit
  } else if (!held.empty()) {
    problem.SetManifold(p.data(), new ceres::SubsetManifold(kMaxParams, held));
  }

  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  so.max_num_iterations = max_iterations;
  so.num_threads = 2;
  so.function_tolerance = 1e-10;
  so.parameter_tolerance = 1e-10;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  FitReport out;
  out.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  if (summary.IsSolutionUsable()) {
    p.resize(used);
    m.unflatten(p);
  }
  out.residuals = residuals(m, d, rows);
  double ss = 0.0, n = 0.0;
  for (const double v : out.residuals) {
    if (std::isnan(v)) continue;
    ss += v * v;
    n += 1.0;
  }
  out.rmse = n > 0 ? std::sqrt(ss / n) : 0.0;
  return out;
}

RowsJacobian residual_jacobian(const ExtendedModel& m, const fit::FitData& d, std::span<const std::size_t> rows) {
  std::vector<double> p = m.flat();
  RowsJacobian out;
  out.n = p.size();
  if (p.size() > static_cast<std::size_t>(kMaxParams))
    throw std::invalid_argument("discrepancy: too many effect parameters in one model");
  p.resize(kMaxParams, 0.0);
  const Layout L = layout_of(m);
  const std::vector<RowInputs> in = row_inputs(d, rows, m);
  std::vector<double> torque(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) torque[j] = d.torque[rows[j]];
  std::vector<double> r(kChunk), J(kChunk * static_cast<std::size_t>(kMaxParams));
  for (std::size_t s = 0; s < in.size(); s += kChunk) {
    const std::size_t len = std::min(kChunk, in.size() - s);
    const ceres::AutoDiffCostFunction<ChunkCost, ceres::DYNAMIC, kMaxParams> cost(
        new ChunkCost{&L, std::span(in).subspan(s, len), std::span<const double>(torque).subspan(s, len)},
        static_cast<int>(len));
    const double* params[] = {p.data()};
    double* jac[] = {J.data()};
    if (!cost.Evaluate(params, r.data(), jac)) throw std::runtime_error("discrepancy: the model is not finite");
    for (std::size_t j = 0; j < len; ++j) {
      if (!in[s + j].described) continue;
      out.residuals.push_back(r[j]);
      const double* row = J.data() + j * static_cast<std::size_t>(kMaxParams);
      out.jacobian.insert(out.jacobian.end(), row, row + out.n);
    }
  }
  return out;
}

std::vector<double> residuals(const ExtendedModel& m, const fit::FitData& d,
                              std::span<const std::size_t> rows) {
  const Layout L = layout_of(m);
  const std::vector<double> p = m.flat();
  const std::vector<RowInputs> in = row_inputs(d, rows, m);
  const auto base = model::ThesisModel<double>::from_params(p.data());
  std::vector<double> r(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    r[j] = in[j].described          ? d.torque[rows[j]] - extended_torque(L, p.data(), base, in[j])
           : std::isnan(in[j].wound) ? std::numeric_limits<double>::quiet_NaN()
                                     : d.torque[rows[j]] - in[j].wound;
  }
  return r;
}

}  // namespace knoblab::discovery::detail
