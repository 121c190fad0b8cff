// DigitalLines on the Linux GPIO character device, through libgpiod v2.
// Each role is its own line request, found by name (gpio_chips.hpp).
//
// Realtime cost per cycle: read() = one GPIO_V2_LINE_GET_VALUES ioctl per input
// plus one zero-timeout poll() on the footswitch request (and a read() of the
// pending events into a preallocated buffer when there are any); write() = one
// SET_VALUES ioctl per output whose value changed. None allocate or block;
// the ioctls take a spinlock/mutex in gpiolib, acceptable on PREEMPT_RT.
// Presses are counted from the kernel's per-line event sequence number, so an
// overflowing event queue can drop events but never presses.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>

#include "knoblab/hal/digital_lines.hpp"
#include "knoblab/hal/gpio_chips.hpp"
#include "knoblab/hal/gpiod_config.hpp"

struct gpiod_line_request;
struct gpiod_edge_event_buffer;

namespace knoblab::hal {

class GpiodLines final : public DigitalLines {
 public:
  // Finds and requests every line; outputs start inactive (amp disabled, LED
  // off). Throws std::runtime_error naming the chip/line on any failure.
  explicit GpiodLines(const GpiodLinesConfig& config);
  // Drives the outputs inactive before releasing the lines.
  ~GpiodLines() override;
  GpiodLines(const GpiodLines&) = delete;
  GpiodLines& operator=(const GpiodLines&) = delete;

  capture::IoStatus read(DigitalInputs& in) override;
  capture::IoStatus write(const DigitalOutputs& out) override;
  std::uint64_t io_errors() const override { return io_errors_.load(std::memory_order_relaxed); }

  // Where each role was found, for the startup log.
  const LineLocation& location(LineRole role) const { return lines_[index(role)].where; }

 private:
  struct RequestDeleter {
    void operator()(gpiod_line_request* r) const;
  };
  struct BufferDeleter {
    void operator()(gpiod_edge_event_buffer* b) const;
  };
  struct Line {
    LineLocation where;
    std::unique_ptr<gpiod_line_request, RequestDeleter> request;
    int written = -1;  // last value written successfully (-1: unknown)
  };
  static constexpr std::size_t index(LineRole role) { return static_cast<std::size_t>(role); }
  bool set(Line& line, bool active);  // false: the write failed (retried next call)

  std::array<Line, 4> lines_;
  std::unique_ptr<gpiod_edge_event_buffer, BufferDeleter> events_;
  std::uint64_t presses_ = 0;
  std::atomic<std::uint64_t> io_errors_{0};
};

}  // namespace knoblab::hal
