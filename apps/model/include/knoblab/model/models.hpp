// The knob models of the thesis as compositions of the torque terms.
//   ThesisModel  — Eq. 6: inertia + asymmetric Coulomb/viscous + detents
//   RenderModel  — Eq. 14: inertia + viscous + detents (no phase), with an
//                  optional Karnopp stick band (Eq. 7) and the effect
//                  library's renderable terms (effect_set.hpp)
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "knoblab/model/effect_set.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::model {

// Parameter order of the thesis model; also the order of the fit's vector
// and the names the JSON output uses.
enum ThesisParam : std::size_t {
  kM_acc, kC_vel_neg, kB_vel_neg, kC_vel_pos, kB_vel_pos, kA_pos, kP_pos, kS_pos,
  kThesisParamCount
};
inline constexpr std::array<std::string_view, kThesisParamCount> kThesisParamNames = {
    "M_acc", "C_vel_neg", "B_vel_neg", "C_vel_pos", "B_vel_pos", "A_pos", "P_pos", "S_pos"};

template <typename T>
struct TorqueParts {
  T acc{}, vel{}, pos{};
  T total() const { return acc + vel + pos; }
};

template <typename T>
struct ThesisModel {
  Inertia<T> inertia;
  CoulombViscous<T> friction;
  Detents<T> detents;

  static ThesisModel from_params(const T* p) {
    ThesisModel m;
    m.inertia.M = p[kM_acc];
    m.friction = {p[kC_vel_neg], p[kB_vel_neg], p[kC_vel_pos], p[kB_vel_pos]};
    m.detents.A = p[kA_pos];
    m.detents.P = p[kP_pos];
    m.detents.S = p[kS_pos];
    return m;
  }

  TorqueParts<T> parts(const Kinematics<T>& k) const {
    return {inertia.torque(k.alpha), friction.torque(k.omega), detents.torque(k.theta)};
  }
  T torque(const Kinematics<T>& k) const { return parts(k).total(); }
};

template <typename T>
struct RenderModel {
  Inertia<T> inertia;
  T B_vel{};
  Detents<T> detents;  // S stays 0 when rendering (Eq. 14)
  bool stick_enabled = false;
  KarnoppStick<T> stick;
  EffectSet<T> effects;  // detent_shape's harmonics: effects.shape_detents(detents)

  CoulombViscous<T> sliding() const { return {T(0), B_vel, T(0), B_vel}; }

  // tau_applied: the torque the hand applies to the knob (the sensor's
  // reading, or 0 where there is none). It only matters in the stick band,
  // where friction holds the knob against what the other terms leave over:
  // in the sensor convention τ = acc + vel + pos, so vel = τ − acc − pos.
  // The effects' position torques count with the detents; their friction
  // terms, like the viscous one, only outside the band.
  T torque(const Kinematics<T>& k, const T& tau_applied = T(0)) const {
    const T pos = detents.torque(k.theta) + effects.held(k.theta, k.omega);
    const T acc = inertia.torque(k.alpha);
    const T vel = stick_enabled && stick.sticking(k.omega)
                      ? stick.torque(k.omega, tau_applied - pos - acc, sliding())
                      : sliding().torque(k.omega) + effects.sliding(k.omega);
    return acc + vel + pos;
  }
};

}  // namespace knoblab::model
