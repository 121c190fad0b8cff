#include "knoblab/hal/memory_lines.hpp"

namespace knoblab::hal {

capture::IoStatus MemoryLines::read(DigitalInputs& in) {
  if (fail_reads_.load(std::memory_order_relaxed)) {
    io_errors_.fetch_add(1, std::memory_order_relaxed);
    in.estop = true;  // an unreadable e-stop is an asserted one
    return capture::IoStatus::error;
  }
  in.estop = !estop_level_high_.load(std::memory_order_relaxed);  // active low
  in.capture_button = button_down_.load(std::memory_order_relaxed);
  in.capture_presses = presses_.load(std::memory_order_relaxed);
  return capture::IoStatus::ok;
}

capture::IoStatus MemoryLines::write(const DigitalOutputs& out) {
  amp_enable_.store(out.amp_enable, std::memory_order_relaxed);
  status_led_.store(out.status_led, std::memory_order_relaxed);
  writes_.fetch_add(1, std::memory_order_relaxed);
  return capture::IoStatus::ok;
}

void MemoryLines::press_capture_button() {
  // Count only the up → down edge, as the kernel's edge detector would.
  if (!button_down_.exchange(true, std::memory_order_relaxed)) presses_.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace knoblab::hal
