// Inertia by virtual-mass coupling (Colgate & Schenkel; thesis §3.3): a
// simulated mass M is tied to the knob angle by a spring K and damper B; the
// coupling torque is what the hand feels as inertia. Backward-Euler
// integration keeps it stable for any M, K, B at the loop rate.
#pragma once

namespace knoblab::hapticd {

class VirtualMass {
 public:
  // Coupling torque (sensor convention: the torque needed to move the knob)
  // for this cycle's knob angle and velocity.
  double update(double M, double K, double B, double theta, double omega, double dt) {
    if (!(M > 0.0)) {
      // No mass: follow the knob so that adding mass later starts at rest.
      x_ = theta;
      v_ = omega;
      return 0.0;
    }
    const double a = dt / M;
    v_ = (v_ + a * (K * (theta - x_) + B * omega)) / (1.0 + a * B + a * dt * K);
    x_ += dt * v_;
    return K * (theta - x_) + B * (omega - v_);
  }

  void reset(double theta, double omega) {
    x_ = theta;
    v_ = omega;
  }

 private:
  double x_ = 0.0, v_ = 0.0;
};

}  // namespace knoblab::hapticd
