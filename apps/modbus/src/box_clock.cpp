#include "knoblab/modbus/box_clock.hpp"

#include <algorithm>

namespace knoblab::modbus {

namespace {
BoxClock::Clock::duration ms(std::uint32_t box_time_ms) { return std::chrono::milliseconds(box_time_ms); }
}  // namespace

void BoxClock::observe(std::uint32_t box_time_ms, Clock::time_point received) {
  const Clock::duration offset = received.time_since_epoch() - ms(box_time_ms);
  if (!valid_ || box_time_ms < last_box_ms_) {
    valid_ = true;
    bucket_start_ms_ = box_time_ms;
    current_min_ = previous_min_ = offset;
  } else if (static_cast<std::int64_t>(box_time_ms - bucket_start_ms_) >= half_window_ms_) {
    previous_min_ = current_min_;
    current_min_ = offset;
    bucket_start_ms_ = box_time_ms;
  } else {
    current_min_ = std::min(current_min_, offset);
  }
  last_box_ms_ = box_time_ms;
}

BoxClock::Clock::time_point BoxClock::to_host(std::uint32_t box_time_ms) const {
  return Clock::time_point(ms(box_time_ms) + std::min(current_min_, previous_min_));
}

}  // namespace knoblab::modbus
