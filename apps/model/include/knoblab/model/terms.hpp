// Torque terms of the knob model: one definition per physics term.
//
// Every term is templated on the scalar type so the same code serves the
// plant simulator (double), the renderer in hapticd (double, no allocation)
// and the fitter (ceres::Jet for automatic differentiation).
//
// Sign convention (thesis Eq. 6 and Eq. 10): a term returns the torque needed
// to move the knob, i.e. the torque the Haptic Camera's sensor reads. Friction
// is C_pos + B_pos·ω for ω > 0 and −C_neg + B_neg·ω for ω < 0, with every
// coefficient a positive magnitude for a dissipative knob.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace knoblab::model {

// sgn that also works for ceres::Jet (compares the value part only).
template <typename T>
T sgn(const T& x) {
  if (x > T(0)) return T(1);
  if (x < T(0)) return T(-1);
  return T(0);
}

// The knob's motion at one instant: position (rad), velocity (rad/s),
// acceleration (rad/s²).
template <typename T>
struct Kinematics {
  T theta{};
  T omega{};
  T alpha{};
};

// τ_acc = M·θ̈ (Eq. 6, acceleration part). M in kg·m² (N·m per rad/s²).
template <typename T>
struct Inertia {
  T M{};
  T torque(const T& alpha) const { return M * alpha; }
};

// Asymmetric Coulomb + viscous friction (Eq. 6, velocity part).
template <typename T>
struct CoulombViscous {
  T C_neg{}, B_neg{}, C_pos{}, B_pos{};
  T torque(const T& omega) const {
    if (omega > T(0)) return C_pos + B_pos * omega;
    if (omega < T(0)) return -C_neg + B_neg * omega;
    return T(0);
  }
  // Under presliding hysteresis (Dahl's state z ∈ [−1, 1], DahlFriction in
  // effects.hpp): the Coulomb part as C·z (C_pos for z ≥ 0, C_neg below),
  // the viscous part unchanged. The plant renders it, discovery fits it.
  T torque_dahl(const T& omega, const T& z) const {
    const T coulomb = (z >= T(0) ? C_pos : C_neg) * z;
    if (omega > T(0)) return coulomb + B_pos * omega;
    if (omega < T(0)) return coulomb + B_neg * omega;
    return coulomb;
  }
};

// Karnopp stick band (Eq. 7). Inside |ω| < dv the knob is taken as stuck:
// friction balances the other torques up to the static limits D_neg / D_pos.
// Outside the band the sliding law applies. Eq. 7 as printed bounds only one
// side in each half of the band (max(D−, τ_other) for ω < 0, min(D+, τ_other)
// for ω > 0); we bound both sides across the whole band, so a knob creeping
// at −Δv/2 still cannot be held by more than D_pos when pushed forward.
template <typename T>
struct KarnoppStick {
  T dv{};     // rad/s, half-width of the zero-velocity band
  T D_neg{};  // N·m, static friction magnitude for negative torque
  T D_pos{};  // N·m, static friction magnitude for positive torque

  bool sticking(const T& omega) const { return omega < dv && omega > -dv; }

  // tau_other: the non-frictional torque currently applied to the knob.
  T torque(const T& omega, const T& tau_other,
           const CoulombViscous<T>& sliding) const {
    if (!sticking(omega)) return sliding.torque(omega);
    if (tau_other > D_pos) return D_pos;
    if (tau_other < -D_neg) return -D_neg;
    return tau_other;
  }
};

// Sinusoidal detents A·sin(θ/P + S) (Eq. 6, position part), with optional
// harmonics of the same period for non-sinusoidal detent shapes:
//   Σ_k a_k·sin(k·φ) + b_k·cos(k·φ),  φ = θ/P + S,  k = 2 … harmonics.
// P is in rad per radian of phase: detents per revolution = 1/P.
// `harmonics` is structure, not a value: every harmonic up to it is always
// evaluated, so a fitter can move a coefficient that starts at zero.
template <typename T>
struct Detents {
  static constexpr std::size_t kMaxHarmonic = 6;
  T A{}, P{1}, S{};
  std::array<T, kMaxHarmonic + 1> a{};  // a[k], b[k] for k >= 2; 0, 1 unused
  std::array<T, kMaxHarmonic + 1> b{};
  std::size_t harmonics = 1;  // highest harmonic evaluated (1 = pure sine)
  bool operator==(const Detents&) const = default;

  T phase(const T& theta) const { return theta / P + S; }
  T torque(const T& theta) const {
    using std::cos;
    using std::sin;
    const T phi = phase(theta);
    T tau = A * sin(phi);
    const std::size_t top = harmonics < kMaxHarmonic ? harmonics : kMaxHarmonic;
    for (std::size_t k = 2; k <= top; ++k) {
      const T kphi = T(static_cast<double>(k)) * phi;
      tau += a[k] * sin(kphi) + b[k] * cos(kphi);
    }
    return tau;
  }
};

// The same detent torque spelled with A >= 0 and S in (-pi, pi], so equal
// terms print alike: A -> -A with S -> S + pi leaves A*sin(theta/P + S) as it
// was, and multiplies harmonic k by (-1)^k, which the harmonics undo.
inline Detents<double> canonical(Detents<double> d) {
  constexpr double kPi = 3.14159265358979323846;
  if (d.A < 0) {
    d.A = -d.A;
    d.S += kPi;
    for (std::size_t k = 3; k <= Detents<double>::kMaxHarmonic; k += 2) d.a[k] = -d.a[k], d.b[k] = -d.b[k];
  }
  d.S = std::remainder(d.S, 2 * kPi);
  if (d.S <= -kPi) d.S += 2 * kPi;
  return d;
}

// Detents per revolution of a detent period P.
inline double cycles_per_rev(const Detents<double>& d) { return 1.0 / d.P; }

// Restoring spring K·(θ−θ0) + K3·(θ−θ0)³ (a ramp, the thesis' K_pos·θ).
template <typename T>
struct Spring {
  T K{}, theta0{}, K3{};
  bool operator==(const Spring&) const = default;
  T torque(const T& theta) const {
    const T d = theta - theta0;
    return K * d + K3 * d * d * d;
  }
};

// Walls: stiff spring and damper beyond [lo, hi], nothing inside.
// The damper only acts while penetrating, so leaving a wall is not sticky.
// The spring's torque tops out at ±limit (N·m): a rendered wall holds at
// the torque its designer (or the motor's limit) gives it rather than
// climbing on as a mechanical stop does (limit ∞, the default).
template <typename T>
struct Walls {
  T lo{-1e9}, hi{1e9};  // rad
  T K{}, B{};           // N·m/rad, N·m·s/rad
  T limit{std::numeric_limits<double>::infinity()};  // N·m
  bool operator==(const Walls&) const = default;
  T torque(const T& theta, const T& omega) const {
    if (theta > hi) {
      const T spring = K * (theta - hi);
      return (spring > limit ? limit : spring) + B * omega;
    }
    if (theta < lo) {
      const T spring = K * (theta - lo);
      return (spring < -limit ? -limit : spring) + B * omega;
    }
    return T(0);
  }
};

}  // namespace knoblab::model
