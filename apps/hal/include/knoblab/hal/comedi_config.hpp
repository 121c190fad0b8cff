// Configuration of the Comedi DAQ backend (a DAS1602-class board: torque and
// accelerometer on analog inputs, motor command on an analog output, the
// quadrature encoder on a counter — on the same or a separate device).
// Format and examples: docs/hal.md.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace knoblab::hal {

enum class Aref { Ground, Common, Diff, Other };

struct VoltRange {
  double min_V = 0.0;
  double max_V = 0.0;
};

struct AnalogChannelConfig {
  std::optional<unsigned> subdevice{};  // empty: the device's first AI (or AO) subdevice
  unsigned channel = 0;
  std::optional<unsigned> range{};       // index into the channel's range table, or
  std::optional<VoltRange> range_V{};   // the table entry with these limits; neither: index 0
  Aref aref = Aref::Ground;
  // Inputs report gain·V + offset_V (e.g. to undo an external divider);
  // the output writes gain·command_V (e.g. −1 for a reversed motor).
  double gain = 1.0;
  double offset_V = 0.0;  // inputs only
};

struct CounterConfig {
  std::string device{};               // empty: the board's own device
  std::optional<unsigned> subdevice{};  // empty: the device's first counter subdevice
  unsigned channel = 0;
  bool reset_on_open = false;  // INSN_CONFIG_RESET at startup
  int sign = 1;                // −1 when the encoder counts the other way round
};

struct ComediDaqConfig {
  std::string device{};  // e.g. "/dev/comedi0"
  AnalogChannelConfig torque{};
  AnalogChannelConfig accel{};
  AnalogChannelConfig motor{};
  CounterConfig encoder{};
};

// Throws ConfigError naming the key (prefixed by `where`).
ComediDaqConfig parse_comedi_config(const nlohmann::json& config, std::string_view where = "daq");

}  // namespace knoblab::hal
