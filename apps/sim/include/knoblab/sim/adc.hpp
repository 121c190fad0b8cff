// A/D converter: bipolar, `bits` wide over ±range volts, round-to-nearest,
// clipping at the end codes. Default 16 bit over ±10 V (lsb 0.305 mV).
#pragma once

#include <algorithm>
#include <cmath>

namespace knoblab::sim {

struct AdcParams {
  int bits = 16;
  double range = 10.0;  // V

  double lsb() const { return 2.0 * range / std::ldexp(1.0, bits); }
  double quantize(double volts) const {
    const double step = lsb();
    const double top = std::ldexp(1.0, bits - 1);
    const double code = std::clamp(std::round(volts / step), -top, top - 1.0);
    return code * step;
  }
};

}  // namespace knoblab::sim
