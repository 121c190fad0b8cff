// Maps the biometrics box's millisecond clock onto the host's steady clock,
// so each 32 Hz sample is stamped with when the box took it rather than when
// a poll happened to read it. A poll sees the box's newest sample some time
// after it was taken (its age in the ring + transit + however late the poll
// ran); the least-delayed poll in a recent window bounds that best, so
//   offset = min over the window of (received − box_time),
//   taken  = box_time + offset.
// A late poll (a busy host) then cannot bunch the samples it finds together:
// each keeps the box's own spacing. The window is short enough that the two
// crystals' drift (≈ 50 ppm: 0.2 ms in 4 s) does not matter.
#pragma once

#include <chrono>
#include <cstdint>

namespace knoblab::modbus {

class BoxClock {
 public:
  using Clock = std::chrono::steady_clock;

  explicit BoxClock(std::chrono::milliseconds window = std::chrono::seconds(4)) : half_window_ms_(window.count() / 2) {}

  // A poll received a sample the box took at box_time_ms. A box clock that
  // goes backwards (the box restarted) starts the estimate over.
  void observe(std::uint32_t box_time_ms, Clock::time_point received);

  // When the box took a sample, on the host clock. Call after observe().
  Clock::time_point to_host(std::uint32_t box_time_ms) const;

 private:
  // Two buckets of half a window each: the estimate is the smaller of the
  // current and the previous bucket's minimum, so it always covers between
  // half a window and a whole one, in O(1) memory.
  std::int64_t half_window_ms_;
  bool valid_ = false;
  std::uint32_t last_box_ms_ = 0;
  std::uint32_t bucket_start_ms_ = 0;
  Clock::duration current_min_{};
  Clock::duration previous_min_{};
};

}  // namespace knoblab::modbus
