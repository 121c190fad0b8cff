// The thesis model (Eq. 6) plus effects from the library: its parameter
// layout, per-row inputs and torque (templated for Ceres autodiff), and the
// fit. Internal to knoblab_discovery.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "knoblab/discovery/effects.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/model/effects.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::discovery::detail {

inline constexpr int kMaxParams = 24;  // Eq. 6's 8 and room for effects
inline constexpr std::size_t kShapeHarmonics = 4;  // detent_shape: harmonics 2 … 4

// An effect in the model: continuous parameters (fitted by Ceres) and, for
// the operators, a setting found by search on a grid (backlash width,
// presliding angle, delay, clip limit, drift's t0).
struct ActiveEffect {
  EffectId id{};
  std::vector<double> params;
  double setting = 0.0;
  // compliance only: the coupling's damping over its stiffness, c/k (s) —
  // the twist follows τ/k through a first-order lag of this time constant.
  double lag_s = 0.0;
  // compliance only: the knob behind the coupling simulated from the
  // motor's motion (coupled_knob.hpp) rather than read off the measured
  // torque.
  bool simulated = false;
  // Part of a given model held fixed (discrepancy --model): not fitted.
  bool held = false;
  // Bit k: params[k] held at its value, a nested, simpler form of the
  // effect (a linear spring: K₃ = 0).
  std::uint32_t fixed = 0;
  bool fitted(std::size_t k) const { return !held && ((fixed >> k) & 1u) == 0; }
};

// What an effect adds to the model's freedom: its fitted parameters and, for
// an operator, the settings searched on a grid (a coupling: stiffness and
// damping).
inline std::size_t parameter_count(const ActiveEffect& e) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < e.params.size(); ++k) n += ((e.fixed >> k) & 1u) == 0 ? 1 : 0;
  switch (e.id) {
    case EffectId::TimeDelay:
    case EffectId::Saturation:
    case EffectId::Backlash:
    case EffectId::Hysteresis:
    case EffectId::Endstop: return n + 1;
    case EffectId::Compliance: return n + 2;
    default: return n;
  }
}

struct ExtendedModel {
  std::vector<double> base;  // Eq. 6, fit order
  std::vector<bool> base_fitted;
  std::vector<ActiveEffect> effects;
  // Below this speed the sliding law does not hold (the knob is held by
  // static friction): a row whose model inputs are slower is not described
  // by the model (RowInputs::described), wherever the operators moved it.
  double stick_speed = 0.0;
  // The base fit's Karnopp band (Eq. 7): a backlash mechanism standing
  // (slower than stick_band) is held by static friction up to `breakaway`
  // (N·m; 0 when the fit has no band: kinetic C± then).
  double stick_band = 0.0, breakaway = 0.0;

  bool has(EffectId id) const;
  // Eq. 6's detent term is in the model: fitted, or held at a given amplitude.
  bool has_detents() const;
  // A compliance in its simulated form: the base's terms are then held
  // (unless refit_behind_coupling), the fit seeing only the sliding rows.
  bool simulates_coupling() const;
  bool refit_behind_coupling = false;
  const ActiveEffect* find(EffectId id) const;
  std::vector<double> flat() const;   // base then every effect's params
  std::vector<bool> free_mask() const;  // per flat() entry: fitted (not held or fixed)
  void unflatten(std::span<const double> p);
};

// What the torque function reads for one row: the motion (delayed when a
// time_delay is in the model), the knob's shift and contact under backlash,
// the Dahl state under hysteresis.
struct RowInputs {
  double t = 0.0, theta = 0.0, omega = 0.0, alpha = 0.0;
  double theta_shift = 0.0;  // backlash: knob − drive
  bool contact = true;       // backlash: the drive moves the knob
  double z = 0.0;            // hysteresis: friction state, −1 … 1
  // compliance: the coupling torque the motor has wound up while the knob
  // stands (row_inputs); NaN while it moves. Predicts a row not `described`.
  double wound = std::numeric_limits<double>::quiet_NaN();
  // The inputs are outside the stick band (ExtendedModel::stick_speed): a
  // delay or a coupling's twist can move a moving row's inputs into it.
  bool described = true;
};

// v at the fractional sample index x (linear between neighbours, clamped to
// the ends): a channel read a delay's fraction of a sample off the grid.
inline double value_at(const std::vector<double>& v, double x) {
  x = std::clamp(x, 0.0, static_cast<double>(v.size() - 1));
  const auto lo = static_cast<std::size_t>(x);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (x - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

// Rows of `d` (indices `rows`) with the operator settings of `m` applied.
// The operators run over the whole recording in time order, whatever rows
// are asked for.
std::vector<RowInputs> row_inputs(const fit::FitData& d, std::span<const std::size_t> rows,
                                  const ExtendedModel& m);

// Where each effect's parameters sit in the flat vector.
struct Layout {
  std::vector<ActiveEffect> effects;  // settings; params zero, their count the effect's form
  std::vector<int> offset;            // per effect
  bool base_detents = true;
  double t_mid = 0.0;                 // drift's reference time
};
Layout layout_of(const ExtendedModel& m);

// `base`: Eq. 6's terms from p (ThesisModel::from_params), made once by the
// caller for many rows: from_params copies every parameter, a Jet each under
// autodiff.
template <typename T>
T extended_torque(const Layout& L, const T* p, const model::ThesisModel<T>& base, const RowInputs& r) {
  using std::cos;
  using std::sin;
  T offset(0);
  const ActiveEffect* hysteresis = nullptr;
  const ActiveEffect* saturation = nullptr;
  for (std::size_t e = 0; e < L.effects.size(); ++e) {
    if (L.effects[e].id == EffectId::Offset) offset += p[L.offset[e]];
    if (L.effects[e].id == EffectId::Hysteresis) hysteresis = &L.effects[e];
    if (L.effects[e].id == EffectId::Saturation) saturation = &L.effects[e];
  }
  // The knob's own inertia is felt inside a play too; the mechanism behind
  // it (friction, position torques) only in contact.
  T tau = offset + base.inertia.torque(T(r.alpha));
  if (r.contact) {
    const T theta = T(r.theta + r.theta_shift), omega(r.omega);
    if (hysteresis) {
      tau += base.friction.torque_dahl(omega, T(r.z));
    } else {
      tau += base.friction.torque(omega);
    }
    if (L.base_detents) tau += base.detents.torque(theta);
    for (std::size_t e = 0; e < L.effects.size(); ++e) {
      const T* q = p + L.offset[e];
      switch (L.effects[e].id) {
        case EffectId::Gravity: tau += model::OncePerRev<T>{q[0], q[1]}.torque(theta); break;
        case EffectId::Spring: {
          model::Spring<T> s;
          s.K = q[0];
          s.K3 = q[1];
          s.theta0 = q[2];
          tau += s.torque(theta);
          break;
        }
        case EffectId::PeriodicTorque: {
          model::Detents<T> w;
          w.A = q[0];
          w.P = q[1];
          w.S = q[2];
          tau += w.torque(theta);
          break;
        }
        case EffectId::DetentShape: {
          const T phi = theta / p[model::kP_pos] + p[model::kS_pos];
          for (std::size_t k = 0; k + 2 <= kShapeHarmonics; ++k) {
            const T kphi = T(static_cast<double>(k + 2)) * phi;
            tau += q[2 * k] * sin(kphi) + q[2 * k + 1] * cos(kphi);
          }
          break;
        }
        case EffectId::Stribeck: tau += model::Stribeck<T>{q[0], q[1]}.torque(omega); break;
        case EffectId::NonlinearDamping:
          tau += model::PowerDamping<T>{q[0], q[1]}.torque(omega);
          break;
        case EffectId::PositionFriction:
          tau += model::PositionFriction<T>{q[0], q[1], q[2]}.torque(theta, omega);
          break;
        case EffectId::Drift:
          tau += model::FrictionDrift<T>{q[0], T(L.t_mid)}.torque(omega, T(r.t));
          break;
        case EffectId::Endstop: {
          model::Walls<T> w;
          w.lo = T(-L.effects[e].setting);
          w.hi = T(L.effects[e].setting);
          w.K = q[0];
          if (L.effects[e].params.size() > 1) w.limit = q[1];  // the saturating form
          tau += w.torque(theta, omega);
          break;
        }
        default: break;  // operators: applied through the row inputs
      }
    }
  }
  if (saturation) tau = model::saturate(tau, T(saturation->setting));
  return tau;
}

// Least squares of the extended model over the rows it describes (Ceres,
// autodiff, every parameter of the flat vector free except held base ones).
// Returns the RMS residual over those rows, and the residuals themselves
// (residuals(): NaN where nothing predicts a row).
struct FitReport {
  double rmse = 0.0;
  int iterations = 0;
  std::vector<double> residuals;
};
FitReport fit_extended(ExtendedModel& m, const fit::FitData& d, std::span<const std::size_t> rows,
                       int max_iterations = 50);

// Residuals (model − measured, as the fit's cost) and their Jacobian
// (row-major, rows × the flat vector's size) over the rows of `rows` the model describes, in time
// order: what fit::covariance_from_rows takes for the intervals.
struct RowsJacobian {
  std::vector<double> residuals, jacobian;
  std::size_t n = 0;  // columns: m.flat().size()
};
RowsJacobian residual_jacobian(const ExtendedModel& m, const fit::FitData& d, std::span<const std::size_t> rows);

// Residuals (measured − model) at the rows; NaN where the model does not
// describe the row (RowInputs::described) and, under compliance, the knob
// does not stand either (RowInputs::wound).
std::vector<double> residuals(const ExtendedModel& m, const fit::FitData& d,
                              std::span<const std::size_t> rows);

}  // namespace knoblab::discovery::detail
