// What a recording holds at a glance, and its detents: the torque-versus-
// position spectrum (angular periodogram, cycles per revolution).
#pragma once

#include <optional>

#include "knoblab/interchange/capture.hpp"

namespace knoblab::cli {

struct CaptureSummary {
  std::size_t samples = 0;
  double duration_s = 0, mean_rate_hz = 0;
  double theta_min = 0, theta_max = 0;    // rad
  double torque_min = 0, torque_max = 0, torque_rms = 0;  // N·m
  double omega_max_abs = 0;               // rad/s
  // Strongest position-periodic torque between 1 and 64 cycles/rev, if the
  // knob turned far enough (over at least one period) to tell.
  std::optional<double> detent_cycles_per_rev;
  double detent_amplitude = 0;  // N·m
  double detent_power = 0;      // fraction of torque variance it explains
};

CaptureSummary summarize(const interchange::Capture& capture);

}  // namespace knoblab::cli
