// The digital I/O hapticd needs, by role rather than by pin: amplifier enable
// and status LED out; e-stop and capture button (footswitch) in. Like
// capture::Daq, the loop calls read() → update → write() once per cycle.
// Values are logical: `estop == true` means "stop", whatever the wiring.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "knoblab/capture/daq.hpp"

namespace knoblab::hal {

struct DigitalInputs {
  bool estop = true;                  // fail-safe default: asserted until read
  bool capture_button = false;        // held down right now
  std::uint64_t capture_presses = 0;  // presses since start; grows by one per press
};

struct DigitalOutputs {
  bool amp_enable = false;
  bool status_led = false;
};

class DigitalLines {
 public:
  virtual ~DigitalLines() = default;
  // Called from the realtime loop: no allocation, never blocks. Each backend
  // documents what a call costs. A failed e-stop read reports estop = true.
  // `error` when any line failed this call.
  [[nodiscard]] virtual capture::IoStatus read(DigitalInputs& in) = 0;
  [[nodiscard]] virtual capture::IoStatus write(const DigitalOutputs& out) = 0;
  // Line reads/writes that failed since start (readable from any thread).
  virtual std::uint64_t io_errors() const = 0;
};

enum class LineRole { AmpEnable, Estop, CaptureButton, StatusLed };

inline constexpr std::array<LineRole, 4> kLineRoles = {LineRole::AmpEnable, LineRole::Estop,
                                                       LineRole::CaptureButton, LineRole::StatusLed};

// The role's key in configuration ("amp_enable", "estop", …).
constexpr std::string_view role_key(LineRole role) {
  switch (role) {
    case LineRole::AmpEnable: return "amp_enable";
    case LineRole::Estop: return "estop";
    case LineRole::CaptureButton: return "capture_button";
    case LineRole::StatusLed: return "status_led";
  }
  return "?";
}

constexpr bool is_output(LineRole role) { return role == LineRole::AmpEnable || role == LineRole::StatusLed; }

}  // namespace knoblab::hal
