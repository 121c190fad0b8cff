// The stiffness and damping the render loop can render stably (its Z-width),
// one definition for the renderer (hapticd refuses tiles outside it) and the
// prototyper's UI (which draws it). Pure: no I/O; construction allocates.
//
// The linearised loop. The knob, held by a light grip, is an inertia J
// (device + grip) with physical damping b (device + grip) and the grip's
// stiffness k_g to the hand, driven through a zero-order hold at the loop rate
// by u = −(K·θ_k + B·ω̂_k), held over [t_k, t_k+1). K is the rendered
// torque's local stiffness dτ/dθ, B its local damping dτ/dθ̇, and ω̂
// hapticd's render velocity: the backward difference (θ_k − θ_k−1)/T through
// the Butterworth the SensorFrontEnd designs (order 10, 500 Hz at 10 kHz;
// model::design_butterworth_lowpass, the same call).
//
// What the plant includes, and why. A rigid J alone (J·θ̈ = u − b·θ̇ − k_g·θ)
// gives the classical virtual-wall bound K ≈ 2b/T: 203 N·m/rad with the
// grip's 0.01 N·m·s/rad. The simulated device (apps/sim: amplifier, motor,
// gripper coupling, knob; tests/hapticd/render_stability_sim_test.cpp) holds
// 680 N·m/rad: the encoder and the motor sit on the light rotor (Eq. 3's
// 1e-6 kg·m²), tied to the knob side by the gripper coupling, whose damper
// (0.07 N·m·s/rad) damps the rotor's ring near the Nyquist rate far more than
// the hand does; the amplifier's 2 kHz current loop lags the torque. So the
// default model is two bodies and a first-order actuator:
//   J_r·θ̈_r = τ − k_c·(θ_r − θ) − c_c·(θ̇_r − θ̇)          (encoder: θ_r)
//   J·θ̈    = k_c·(θ_r − θ) + c_c·(θ̇_r − θ̇) − b·θ̇ − k_g·θ
//   τ̇      = ω_a·(u − τ)
// It predicts 711 N·m/rad (+5 %). Setting rotor_inertia or
// coupling_stiffness to 0 gives the rigid body, actuator_bandwidth_hz = 0 an
// ideal actuator. Coulomb friction, the torque limit's clip and encoder
// quantisation are not in it (the test's knob has none of the first).
//
#pragma once

#include <complex>
#include <vector>

#include "knoblab/model/filters.hpp"

namespace knoblab::model {

// Inertia of the haptic knob's mechanism, motor included (thesis §3.3.2:
// 0.013 mN·m/(rad/s²)).
inline constexpr double kHapticDeviceInertia = 0.013e-3;  // kg·m²
// The motor's bearing damping (Eq. 3's b): the device's own, next to nothing.
inline constexpr double kHapticDeviceDamping = 6.87197e-8;  // N·m·s/rad
// The simulated device's rotor (Eq. 3's J), gripper coupling
// (sim/coupling.hpp) and current loop (sim/amplifier.hpp).
inline constexpr double kRotorInertia = 1.0e-6;           // kg·m²
inline constexpr double kCouplingStiffness = 100.0;       // N·m/rad
inline constexpr double kCouplingDamping = 0.07;          // N·m·s/rad
inline constexpr double kActuatorBandwidthHz = 2000.0;
// The grip the bound assumes: the simulator's default hand (docs/hal.md,
// sim/hand.hpp), a light fingertip hold — 1 N·m/rad to where the hand
// is, 0.01 N·m·s/rad, and no inertia of its own. Light is the safe side: less
// inertia and less damping both narrow the region, so a firmer hand (more
// of either) renders at least what this one does.
inline constexpr double kGripStiffness = 1.0;    // N·m/rad
inline constexpr double kGripDamping = 0.01;     // N·m·s/rad
inline constexpr double kGripInertia = 0.0;      // kg·m²

struct LoopDynamics {
  double rate_hz = 10000.0;
  double inertia = kHapticDeviceInertia + kGripInertia;  // J, kg·m²
  double damping = kHapticDeviceDamping + kGripDamping;  // b, N·m·s/rad
  double grip_stiffness = kGripStiffness;                // k_g, N·m/rad
  int velocity_filter_order = 10;                        // SensorConfig's
  double velocity_cutoff_hz = 500.0;                     // render cutoff (Study 3)
  // The two bodies and the actuator (0: off, see the header comment).
  double actuator_bandwidth_hz = kActuatorBandwidthHz;
  double rotor_inertia = kRotorInertia;            // kg·m²; > 0 with coupling_stiffness > 0: two bodies
  double coupling_stiffness = kCouplingStiffness;  // N·m/rad
  double coupling_damping = kCouplingDamping;      // N·m·s/rad
};

// The loop's closed-loop map, built once per LoopDynamics (the plant's
// zero-order-hold discretisation and the filter), tested per (K, B).
class LoopStability {
 public:
  // Throws std::invalid_argument when the dynamics are not physical.
  explicit LoopStability(const LoopDynamics& d);

  const LoopDynamics& dynamics() const noexcept { return d_; }
  // K in N·m/rad, B in N·m·s/rad.
  bool renders_stably(double K, double B) const;
  // The largest modulus among the closed loop's roots that count (see the
  // header comment): ≤ 1 is stable (1: a free knob stays where it is).
  double spectral_radius(double K, double B) const;
  // Bisection on renders_stably, to 1e-4 relative, each returning a stable
  // value. max_stiffness / min_stiffness: the largest K ≥ 0 and the least
  // (most negative: the falling side of a detent) K ≤ 0 with this B;
  // max_damping / min_damping: the largest B ≥ 0 and the least B ≤ 0 with
  // this K. NaN when (0, B) resp. (K, 0) is itself unstable; ±∞ when
  // nothing up to 1e9 either way is unstable.
  double max_stiffness(double B) const;
  double min_stiffness(double B) const;
  double max_damping(double K) const;
  double min_damping(double K) const;

  // The closed-loop state matrix (row-major, n × n), for tests.
  std::vector<double> closed_loop(double K, double B, int& n) const;

 private:
  void step(const double* z, double K, double B, double* next) const;

  LoopDynamics d_;
  int np_ = 0;                  // plant states
  std::vector<double> phi_;     // np × np
  std::vector<double> gamma_;   // np
  int out_ = 0;                 // index of the encoder's angle in the plant state
  std::vector<Sos> filter_;
};

bool renders_stably(const LoopDynamics& d, double K, double B);
double max_stiffness(const LoopDynamics& d, double B);
double max_damping(const LoopDynamics& d, double K);
double min_damping(const LoopDynamics& d, double K);

// Eigenvalues of a real n × n matrix (row-major): balancing, Householder
// Hessenberg reduction, shifted complex QR. Exposed for tests.
std::vector<std::complex<double>> eigenvalues(std::vector<double> a, int n);

}  // namespace knoblab::model
