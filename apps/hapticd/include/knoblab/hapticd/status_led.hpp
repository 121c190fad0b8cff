// The status LED: what the appliance is doing, readable across the room.
//
//   off          a fault is latched or the e-stop is pressed: the motor is safe
//                (also while hapticd is not running)
//   blinking     a capture or calibration run records: leave the knob alone
//                (2 Hz, half on, half off)
//   steady on    ready: idle or rendering (a study trial records in these modes)
//
// A pure function of the cycle's record: realtime-safe, and the blink comes
// from the cycle number, not a clock, so it is the same in simulated time.
#pragma once

#include <cstdint>

#include "knoblab/hapticd/core.hpp"

namespace knoblab::hapticd {

inline constexpr double kStatusLedBlinkHz = 2.0;

// Whether the LED is lit on cycle `cycle` of a loop running at `rate_hz`.
bool status_led(bool safe, Mode mode, std::uint64_t cycle, double rate_hz) noexcept;

// The same for the record HapticCore::cycle just made.
bool status_led(const LoopRecord& record, double rate_hz) noexcept;

}  // namespace knoblab::hapticd
