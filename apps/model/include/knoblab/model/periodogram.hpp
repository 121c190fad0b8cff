// Angular periodogram: how strongly y(θ) repeats with a spatial frequency,
// for samples on an irregular, back-and-forth θ (a swept-sine capture).
//
// For each candidate f (cycles per revolution) it fits, by least squares,
//   y ≈ a·sin(f·θ) + b·cos(f·θ) + c
// (Lomb–Scargle with a floating offset) and reports the fraction of y's
// variance the fit explains, 0..1. The peak's fit is y ≈ A·sin(f·θ + S) + c,
// which maps straight onto the detent term A_pos·sin(θ/P_pos + S_pos) with
// P_pos = 1/f (model::Detents).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace knoblab::model {

struct SinusoidFit {
  double frequency = 0.0;  // cycles/rev
  double power = 0.0;      // explained-variance fraction, 0..1
  double amplitude = 0.0;  // A, units of y
  double phase = 0.0;      // S, rad, in (−π, π]
  double offset = 0.0;     // c, units of y
};

struct AngularPeriodogram {
  std::vector<double> frequency;  // cycles/rev
  std::vector<double> power;      // explained-variance fraction per frequency
  // Best grid frequency refined by a parabola through its neighbours, with
  // the least-squares fit at that frequency.
  SinusoidFit peak;
};

// The least-squares sinusoid at one frequency f (cycles/rev).
// Throws std::invalid_argument if the sizes differ or there are < 3 samples.
SinusoidFit fit_sinusoid(std::span<const double> theta, std::span<const double> y, double f);

// Frequencies f_min, f_min + df, … up to f_max (inclusive, within rounding).
// Costs O(samples × frequencies) multiply-adds and O(samples) trig calls per
// 64 frequencies (angle-addition recurrence in between).
// Throws std::invalid_argument for mismatched sizes, < 3 samples, df <= 0,
// f_min < 0 or f_max < f_min.
AngularPeriodogram angular_periodogram(std::span<const double> theta, std::span<const double> y,
                                       double f_min, double f_max, double df);

}  // namespace knoblab::model
