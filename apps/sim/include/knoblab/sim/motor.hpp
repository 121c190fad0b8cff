// Maxon RE40 DC motor, thesis Eq. 3 (§1.7):
//   L di/dt = V − R·i − K·ω_m        (winding)
//   J dω_m/dt = K·i − b·ω_m − τ_c    (rotor; τ_c is the gripper coupling)
#pragma once

namespace knoblab::sim {

struct MotorParams {
  double K = 0.0438;       // N·m/A, also the back-EMF constant V·s/rad
  double J = 1.0e-6;       // kg·m², rotor
  double b = 6.87197e-8;   // N·m·s/rad, bearing viscous damping
  double L = 8.3e-4;       // H
  double R = 7.73;         // Ω
  // Other rotating parts on the motor side of the gripper coupling (sensor
  // flange, accelerometer housing). Not in the thesis, so 0: Eq. 3 literally.
  double extra_inertia = 0.0;  // kg·m²

  double inertia() const { return J + extra_inertia; }
  double torque(double current) const { return K * current; }

  // One implicit-Euler step of the winding over h: stable for any h, so the
  // electrical pole (R/L ≈ 9300 1/s) never limits the substep.
  double winding_step(double i, double volts, double omega, double h) const {
    return (L / h * i + volts - K * omega) / (L / h + R);
  }

  // Steady free-running speed under a constant voltage (Eq. 3 at s → 0).
  double steady_speed(double volts) const { return K * volts / (b * R + K * K); }
  double electrical_time_constant() const { return L / R; }
};

}  // namespace knoblab::sim
