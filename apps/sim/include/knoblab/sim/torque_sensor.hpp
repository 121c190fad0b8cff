// Honeywell-Sensotec QWFK-8M torque sensor + AD524 amplifier (thesis §1.2.4)
// in the gripper coupling. Model of one sample:
//   τ_meas = clamp(τ_c + offset + σ·n, ±saturation)      (N·m)
//   volts  = ADC(τ_meas × 5 V / 0.1755 N·m)
// * Scale: factory calibration 175.5 mN·m per 5 V.
// * Saturation ±180 mN·m: the knobs' working range is "0–200 mNm" (§2.2) but
//   §2.3.4 stresses the sensor's limited range; 180 mN·m = 5.13 V.
//   The effect library's `saturation:limit_Nm=` sets it (model::saturate, the
//   clip discovery fits).
// * Noise σ = 0.05 mN·m: §2.1.2.3 puts the sensor below 0.1 % peak-to-peak
//   of full scale (0.18 mN·m p-p ≈ 6σ → σ ≈ 0.03 mN·m); rounded up for the
//   motor's electrical pickup (§2.4.2). It sits under Table 1's 0.18 mN·m
//   resolution, as it should; Table 4's 1.8 mN·m SD is tracking error, not
//   sensor noise.
// * Offset: the sensor's zero error, N·m; the capture tares it, so
//   TorqueSensorScale deliberately does not know it.
// * Delay: the amplifier/ADC pipeline of the torque channel, s: a sample at t
//   reads the coupling torque of t − delay while the encoder and the
//   accelerometer read t (discovery's time_delay, delay_s > 0 = torque behind
//   the motion). 0 on the thesis rig; the Plant holds the history.
#pragma once

#include "knoblab/model/effects.hpp"
#include "knoblab/sim/adc.hpp"
#include "knoblab/sim/rng.hpp"

namespace knoblab::sim {

inline constexpr double kTorqueVoltsPerNm = 5.0 / 0.1755;

// Volts ↔ N·m, as a capture converts the ADC channel.
struct TorqueSensorScale {
  double volts_per_Nm = kTorqueVoltsPerNm;
  double to_torque(double volts) const { return volts / volts_per_Nm; }
  double to_volts(double torque) const { return torque * volts_per_Nm; }
};

struct TorqueSensorParams {
  TorqueSensorScale scale{};
  double saturation = 0.180;   // N·m
  double noise_sigma = 0.05e-3;// N·m
  double offset = 0.0;         // N·m
  double delay = 0.0;          // s, ≥ 0 (Plant: ≤ 0.1 s)
  AdcParams adc{};

  // One sample of the (delayed) coupling torque, in ADC volts.
  double sample(double coupling_torque, Rng& rng) const {
    const double noisy = coupling_torque + offset + noise_sigma * rng.normal();
    const double tau = model::saturate(noisy, saturation);
    return adc.quantize(scale.to_volts(tau));
  }
};

}  // namespace knoblab::sim
