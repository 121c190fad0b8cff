#include "knoblab/hapticd/status_led.hpp"

#include <algorithm>
#include <cmath>

#include "knoblab/interchange/sample.hpp"

namespace knoblab::hapticd {

bool status_led(bool safe, Mode mode, std::uint64_t cycle, double rate_hz) noexcept {
  if (safe) return false;
  if (mode != Mode::Capture && mode != Mode::Calibrate) return true;
  // Whole cycles per blink, so every period lights for the same count.
  const auto period = static_cast<std::uint64_t>(std::max(2.0, std::round(rate_hz / kStatusLedBlinkHz)));
  return cycle % period < period / 2;
}

bool status_led(const LoopRecord& r, double rate_hz) noexcept {
  const bool safe = (r.sample.flags & (interchange::kFaultLatched | interchange::kEstopActive)) != 0;
  return status_led(safe, r.mode, r.seq, rate_hz);
}

}  // namespace knoblab::hapticd
