// In-process DigitalLines for host tests and the simulator: the test side
// drives the inputs (at their physical level, like a wire would) and reads
// back what the loop wrote. Every field is atomic, so the loop may run on
// another thread; read()/write() are a handful of relaxed atomic operations.
#pragma once

#include <atomic>
#include <cstdint>

#include "knoblab/hal/digital_lines.hpp"

namespace knoblab::hal {

class MemoryLines final : public DigitalLines {
 public:
  // The e-stop line starts low, i.e. asserted: like an unplugged cable.
  explicit MemoryLines(bool estop_asserted = true) : estop_level_high_(!estop_asserted) {}

  capture::IoStatus read(DigitalInputs& in) override;
  capture::IoStatus write(const DigitalOutputs& out) override;
  std::uint64_t io_errors() const override { return io_errors_.load(std::memory_order_relaxed); }

  // --- test side: inputs -------------------------------------------------
  // ESTOP_N is active low: physical low means e-stop asserted.
  void set_estop_level(bool high) { estop_level_high_.store(high, std::memory_order_relaxed); }
  void press_estop() { set_estop_level(false); }
  void release_estop() { set_estop_level(true); }
  // A press counts once, on the edge; pressing a held button does nothing.
  void press_capture_button();
  void release_capture_button() { button_down_.store(false, std::memory_order_relaxed); }
  void click_capture_button() {
    press_capture_button();
    release_capture_button();
  }
  // While set, read() fails like a broken ioctl: e-stop reported, error counted.
  void set_read_failure(bool fail) { fail_reads_.store(fail, std::memory_order_relaxed); }

  // --- test side: what the loop wrote ------------------------------------
  bool amp_enable() const { return amp_enable_.load(std::memory_order_relaxed); }
  bool status_led() const { return status_led_.load(std::memory_order_relaxed); }
  std::uint64_t writes() const { return writes_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> estop_level_high_;
  std::atomic<bool> button_down_{false};
  std::atomic<std::uint64_t> presses_{0};
  std::atomic<bool> fail_reads_{false};
  std::atomic<std::uint64_t> io_errors_{0};
  std::atomic<bool> amp_enable_{false};
  std::atomic<bool> status_led_{false};
  std::atomic<std::uint64_t> writes_{0};
};

}  // namespace knoblab::hal
