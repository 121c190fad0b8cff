// Bumpless parameter changes: each new target is reached by a linear ramp
// over a fixed time, so a slider drag can never make a torque step.
#pragma once

namespace knoblab::hapticd {

class ParamRamp {
 public:
  explicit ParamRamp(double value = 0.0) : value_(value), target_(value) {}

  void retarget(double target, int cycles) {
    target_ = target;
    remaining_ = cycles > 0 ? cycles : 0;
    step_ = remaining_ > 0 ? (target_ - value_) / remaining_ : 0.0;
    if (remaining_ == 0) value_ = target_;
  }
  // Jump straight to a value (loading a new model while idle).
  void set(double value) {
    value_ = target_ = value;
    remaining_ = 0;
  }
  double step() {
    if (remaining_ > 0 && --remaining_ == 0) value_ = target_;
    else if (remaining_ > 0) value_ += step_;
    return value_;
  }
  double value() const { return value_; }
  double target() const { return target_; }

 private:
  double value_, target_, step_ = 0.0;
  int remaining_ = 0;
};

}  // namespace knoblab::hapticd
