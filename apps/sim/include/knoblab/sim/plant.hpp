// The plant simulator: DAC command → amplifier → DC motor → gripper coupling
// (torque sensor) → knob, plus encoder and accelerometer. The `sim` I/O
// backend of the realtime daemon.
//
//   Plant plant(cfg);                       // may allocate, may throw
//   const SensorReadings& r = plant.step(command_volts, 1e-4);  // 10 kHz tick
//
// step() integrates with fixed substeps h = dt/n, n = max(min_substeps,
// ⌈dt/max_substep⌉) (≥ 10 per tick, ≤ 10 µs), allocates nothing and takes no
// locks. The winding and the coupling are integrated implicitly (stiff, but
// linear), the knob's nonlinear terms explicitly with semi-implicit Euler.
// Deterministic: the same config and seed give bit-identical readings; the
// seed only drives sensor noise, so the true motion never depends on it.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "knoblab/model/effects.hpp"
#include "knoblab/sim/accelerometer.hpp"
#include "knoblab/sim/amplifier.hpp"
#include "knoblab/sim/coupling.hpp"
#include "knoblab/sim/delay_line.hpp"
#include "knoblab/sim/effects.hpp"
#include "knoblab/sim/knob.hpp"
#include "knoblab/sim/motor.hpp"
#include "knoblab/sim/mounting.hpp"
#include "knoblab/sim/rng.hpp"
#include "knoblab/sim/sensors.hpp"

namespace knoblab::sim {

// What is on the far side of the gripper coupling.
enum class Load {
  Knob,      // the knob under test (KnobParams)
  Free,      // nothing: the motor spins freely (thesis §2.2.1.1 spatial test)
  Anchored,  // the gripper is clamped (§2.2.1.2 torque test)
};

struct PlantConfig {
  MotorParams motor{};
  AmplifierParams amp{};
  CouplingParams coupling{};
  KnobParams knob{};
  Load load = Load::Knob;
  EncoderScale encoder{};
  TorqueSensorParams torque_sensor{};
  AccelerometerParams accel{};
  CameraOrientation mounting = CameraOrientation::lab();
  int min_substeps = 10;        // per step()
  double max_substep = 10e-6;   // s
  double initial_angle = 0.0;   // rad, motor and knob at rest here
  std::uint64_t seed = 1;
};

// True state (ground truth for tests and captures), SI units.
struct PlantState {
  double t = 0.0;
  double motor_angle = 0.0, motor_velocity = 0.0, motor_accel = 0.0;
  double knob_angle = 0.0, knob_velocity = 0.0, knob_accel = 0.0;
  double current = 0.0, voltage = 0.0;  // winding
  double coupling_torque = 0.0;         // what the torque sensor sees (undelayed)
  bool stuck = false;                   // knob held by the Karnopp band
};

class Plant {
 public:
  // Throws std::invalid_argument when the configuration is not physical.
  explicit Plant(const PlantConfig& cfg);

  // Advances dt seconds under a constant DAC command (V) and samples the
  // sensors at the end. dt ≤ 0 or non-finite: no-op; non-finite command: 0 V.
  const SensorReadings& step(double command_volts, double dt);

  const SensorReadings& readings() const { return readings_; }
  const PlantState& state() const { return state_; }
  const PlantConfig& config() const { return cfg_; }
  const Amplifier& amplifier() const { return amp_; }

  // Back to t = 0 and the initial noise; effects are reset too.
  void reset();
  // Setup time only (allocates). See effects.hpp.
  void add_effect(std::unique_ptr<KnobEffect> effect);

  // How to turn the readings back into SI units.
  const EncoderScale& encoder_scale() const { return cfg_.encoder; }
  const TorqueSensorScale& torque_scale() const { return cfg_.torque_sensor.scale; }
  AccelCalibration accel_calibration() const { return accel_.calibration(); }

 private:
  struct MotorStep {
    double omega;   // new rotor speed
    double torque;  // coupling torque over the substep
  };

  void substep(double command, double h);
  MotorStep motor_against_held_knob(double motor_force, double h) const;
  void step_free(double motor_force, double h);
  void step_held(double motor_force, double h);
  void step_knob(double motor_force, double h);
  int play_face() const;
  double mechanism_free_velocity(double tau_pos) const;
  double sliding_friction(double w) const;
  double effects_torque(const KnobMotion& k) const;
  void sample();

  PlantConfig cfg_;
  Amplifier amp_;
  Accelerometer accel_;
  Rng torque_rng_, accel_rng_;
  model::CoulombViscous<double> bearing_{};  // Eq. 3's b, as a viscous term
  double knob_inertia_ = 0.0;                // M + gripper
  bool dry_friction_ = false;
  std::vector<std::unique_ptr<KnobEffect>> effects_;
  model::Backlash play_{};     // the detent mechanism behind the knob's play
  double mech_velocity_ = 0.0;  // its speed over the last substep
  model::DahlFriction dahl_{};  // presliding state (KnobParams::presliding)
  DelayLine torque_delay_;      // the torque channel's pipeline (TorqueSensorParams::delay)
  PlantState state_{};
  SensorReadings readings_{};
};

}  // namespace knoblab::sim
