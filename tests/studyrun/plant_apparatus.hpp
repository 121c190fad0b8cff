// A stand-in for hapticd in the runner's unit tests: the simulated knob (the
// sim plant with the study knob, motor unpowered) turned by the guided hand,
// with the condition's rendering as a torque on the knob, stepped in
// simulated time, a reading every millisecond. The hapticd_session tests run
// the same sessions through the real hapticd.
#pragma once

#include <cmath>
#include <memory>

#include "knoblab/model/terms.hpp"
#include "knoblab/sim/guided_hand.hpp"
#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"
#include "knoblab/studyrun/apparatus.hpp"

namespace knoblab::test {

class PlantApparatus final : public studyrun::Apparatus {
 public:
  PlantApparatus() : plant_(config()) {
    plant_.add_effect(sim::make_guided_hand(hand_));
    plant_.add_effect(std::make_unique<Rendered>(rendering_));
  }
  sim::HandChannel& hand() { return hand_; }
  void render(const study::Rendering& r) override {
    rendering_ = r;
    ++renders;
  }
  void start_trial(const studyrun::TrialLabel& label) override {
    ++trials_started;
    last_label = label;
  }
  studyrun::TrialRecording stop_trial() override { return {}; }
  studyrun::KnobReading next() override {
    plant_.step(0.0, 1e-3);
    const sim::PlantState& s = plant_.state();
    return {s.t, s.knob_angle, s.knob_velocity, s.coupling_torque};
  }
  const study::Rendering& rendering() const { return rendering_; }

  int renders = 0;
  int trials_started = 0;
  studyrun::TrialLabel last_label;

 private:
  // τ = M·θ̈ + B·θ̇ + A·sin(n·θ): what it takes to move the rendered knob.
  // The inertia is a virtual mass on a stiff spring-damper, as hapticd
  // renders it (an explicit M·θ̈ from the last step would be unstable for a
  // mass larger than the knob's own).
  class Rendered final : public sim::KnobEffect {
   public:
    explicit Rendered(const study::Rendering& r) : r_(r) {}
    double torque(const sim::KnobMotion& k, double) const override {
      const model::Detents<double> detents{.A = r_.A_pos, .P = r_.detents_per_rev > 0 ? 1 / r_.detents_per_rev : 1};
      return coupling(k) + r_.B_vel * k.omega + detents.torque(k.theta);
    }
    void advance(const sim::KnobMotion& k, double, double h) override {
      if (r_.M_acc <= 0) {
        x_ = k.theta, v_ = k.omega;
        return;
      }
      v_ += h * coupling(k) / r_.M_acc;
      x_ += h * v_;
    }

   private:
    static constexpr double kK = 5.0, kB = 0.05;  // N·m/rad, N·m·s/rad
    double coupling(const sim::KnobMotion& k) const {
      return r_.M_acc > 0 ? kK * (k.theta - x_) + kB * (k.omega - v_) : 0.0;
    }
    const study::Rendering& r_;
    double x_ = 0, v_ = 0;
  };
  static sim::PlantConfig config() {
    sim::PlantConfig c;
    c.knob = sim::presets::find("study3-not-rendered")->knob;
    return c;
  }
  sim::HandChannel hand_;
  study::Rendering rendering_;
  sim::Plant plant_;
};

}  // namespace knoblab::test
