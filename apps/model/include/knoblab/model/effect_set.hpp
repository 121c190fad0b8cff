// The effect library's terms a rendered knob can carry on top of Eq. 14,
// fixed in size so the renderer copies it without allocating: each term is
// the one definition in terms.hpp / effects.hpp, summed here.
//
//   held(θ, ω):    torques static friction holds against (offset, gravity,
//                  spring, periodic torques, walls): in the Karnopp band
//                  they belong with the detents in what the hand works against.
//   sliding(ω):    friction beyond the viscous term (Stribeck, power-law
//                  damping), felt only outside the stick band.
//   detent_a/b:    harmonics 2…4 of the model's own detents (detent_shape);
//                  the owner of the detents copies them in (shape_detents).
// Not here, and not renderable from a torque law of the knob's motion:
// backlash and hysteresis (operators with a state between drive and knob),
// drift (a change over a recording's time), position_friction (it modulates
// a Coulomb level that Eq. 14 folds into its damping), and the rig's
// compliance, time delay and saturation.
#pragma once

#include <array>
#include <cstddef>
#include <limits>

#include "knoblab/model/effects.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::model {

template <typename T>
struct EffectSet {
  static constexpr std::size_t kMaxPeriodic = 4;
  static constexpr std::size_t kShapeHarmonics = 3;  // harmonics 2, 3, 4

  Offset<T> offset;
  OncePerRev<T> gravity;
  Spring<T> spring;
  std::array<Detents<T>, kMaxPeriodic> periodic{};
  std::size_t periodic_count = 0;
  std::array<T, kShapeHarmonics> detent_a{}, detent_b{};  // a_k, b_k for k = 2 … 4
  Stribeck<T> stribeck;
  PowerDamping<T> damping{T(0), T(2)};
  Walls<T> walls;

  bool operator==(const EffectSet&) const = default;

  T held(const T& theta, const T& omega) const {
    T tau = offset.torque() + gravity.torque(theta) + spring.torque(theta) + walls.torque(theta, omega);
    for (std::size_t i = 0; i < periodic_count && i < kMaxPeriodic; ++i) tau += periodic[i].torque(theta);
    return tau;
  }
  T sliding(const T& omega) const { return stribeck.torque(omega) + damping.torque(omega); }

  // The detents with this set's harmonics on them.
  void shape_detents(Detents<T>& d) const {
    bool any = false;
    for (std::size_t k = 0; k < kShapeHarmonics; ++k) {
      d.a[k + 2] = detent_a[k];
      d.b[k + 2] = detent_b[k];
      any = any || detent_a[k] != T(0) || detent_b[k] != T(0);
    }
    if (any && d.harmonics < kShapeHarmonics + 1) d.harmonics = kShapeHarmonics + 1;
  }

  // Every term at `g` times its size (each is linear in its amplitude), for
  // fading a set in or out without a torque step.
  EffectSet scaled(const T& g) const {
    EffectSet s = *this;
    s.offset.tau0 *= g;
    s.gravity.A *= g;
    s.spring.K *= g;
    s.spring.K3 *= g;
    for (auto& p : s.periodic) p.A *= g;
    for (auto& a : s.detent_a) a *= g;
    for (auto& b : s.detent_b) b *= g;
    s.stribeck.excess *= g;
    s.damping.c *= g;
    s.walls.K *= g;
    s.walls.B *= g;
    if (s.walls.limit < T(std::numeric_limits<double>::infinity())) s.walls.limit *= g;  // ∞: no limit
    return s;
  }
};

}  // namespace knoblab::model
