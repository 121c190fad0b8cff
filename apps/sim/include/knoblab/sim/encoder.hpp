// MicroE M2000 optical encoder on the motor shaft (thesis §1.2.1): 2500 lines
// × 256 interpolation = 640 000 counts/rev (9.8 µrad). Counts are
// floor(θ_m / step), like an up/down counter zeroed at θ_m = 0; no noise (the
// thesis puts it under 0.1 %, far below one count).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace knoblab::sim {

struct EncoderScale {
  std::int64_t cpr = 640000;

  double rad_per_count() const { return 2.0 * std::numbers::pi / static_cast<double>(cpr); }
  double to_angle(std::int64_t counts) const { return static_cast<double>(counts) * rad_per_count(); }
  std::int64_t to_counts(double theta) const {
    return static_cast<std::int64_t>(std::floor(theta / rad_per_count()));
  }
};

}  // namespace knoblab::sim
