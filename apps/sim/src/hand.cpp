#include "knoblab/sim/hand.hpp"

#include <cmath>
#include <numbers>

namespace knoblab::sim {

namespace {

class Hand final : public KnobEffect {
 public:
  explicit Hand(const HandParams& p) : p_(p), w_(2.0 * std::numbers::pi * p.frequency_hz) {}
  double torque(const KnobMotion& knob, double t) const override {
    const double theta_h = p_.amplitude_rad * std::sin(w_ * t);
    const double omega_h = p_.amplitude_rad * w_ * std::cos(w_ * t);
    return -(p_.stiffness * (theta_h - knob.theta) + p_.damping * (omega_h - knob.omega));
  }

 private:
  HandParams p_;
  double w_;
};

}  // namespace

std::unique_ptr<KnobEffect> make_hand(const HandParams& p) { return std::make_unique<Hand>(p); }

}  // namespace knoblab::sim
