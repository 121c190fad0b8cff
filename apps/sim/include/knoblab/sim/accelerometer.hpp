// ADXL202 on the rotating housing (thesis §1.2.3), tangential at radius r.
// Model of the raw channel:
//   x(t)  = low-pass_bw( α_true + gravity(θ) )            (rad/s²)
//   volts = ADC( clamp(x + σ·n, ±full_scale) / C_cal )
//   gravity(θ) = A_g·sin(θ + roll) + D_g,  A_g = (g/r)·sin(tilt)
// i.e. thesis Eq. 2 with B = 1 and Eq. 12 (C_cal = 1148 (rad/s²)/V).
// * Bandwidth 2.5 kHz: the ADXL202 filter the thesis quotes (§2.1.2.3).
// * Full scale: the ADXL202's ±2 g at r (2g/r = 1307 rad/s² at 15 mm).
// * Noise: §2.1.2.3's "less than 4 % variation" read as 4 % of full scale
//   peak-to-peak, σ = 0.04·FS/6 = 8.7 rad/s² (7.6 mV). Cross-check: the
//   ADXL202's 200 µg/√Hz over 2.5 kHz is 12.6 mg rms = 8.2 rad/s² at 15 mm.
// * Side: on the knob side of the coupling by default (it measures the
//   knob's acceleration, §1.2.3); Side::Motor puts it on the shaft.
#pragma once

#include <numbers>

#include "knoblab/sim/adc.hpp"
#include "knoblab/sim/mounting.hpp"
#include "knoblab/sim/rng.hpp"

namespace knoblab::sim {

inline constexpr double kAccelCcal = 1148.0;  // (rad/s²)/V, Eq. 12

struct AccelerometerParams {
  enum class Side { Knob, Motor };
  Side side = Side::Knob;
  double C_cal = kAccelCcal;       // (rad/s²)/V
  double radius = 0.015;           // m
  double full_scale_g = 2.0;       // ADXL202 ±2 g
  double noise_pp_fraction = 0.04; // of full scale, peak-to-peak
  double bandwidth_hz = 2500.0;    // ≤ 0: no filter
  double offset = 0.0;             // D_g, rad/s² (zero-g offset)
  AdcParams adc{};

  double full_scale() const { return full_scale_g * kGravity / radius; }  // rad/s²
  double noise_sigma() const { return noise_pp_fraction * full_scale() / 6.0; }
};

// The constants a capture stores to undo the simulated accelerometer:
//   α = C_cal·volts − (A·sin(θ/B + C) + D)   (A, D in rad/s²; θ in rad)
struct AccelCalibration {
  double C_cal = kAccelCcal;
  double A = 0.0, B = 1.0, C = 0.0, D = 0.0;

  double gravity(double theta) const;
  double to_alpha(double volts, double theta) const { return C_cal * volts - gravity(theta); }
};

class Accelerometer {
 public:
  Accelerometer(const AccelerometerParams& p, const CameraOrientation& o);

  AccelCalibration calibration() const { return cal_; }
  // Starts the filter at rest at angle theta.
  void reset(double theta);
  // Per substep: feed the true acceleration and angle of the sensor's side.
  void track(double alpha, double theta, double h);
  // One sample, in ADC volts.
  double sample(Rng& rng) const;

 private:
  AccelerometerParams p_;
  AccelCalibration cal_;
  double filtered_ = 0.0;
  double last_h_ = -1.0, coef_ = 1.0;
};

}  // namespace knoblab::sim
