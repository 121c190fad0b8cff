// The `modbus` section of hapticd's configuration file: the servo amplifier
// and the biometrics box, each over its own TCP or RTU endpoint, and the
// polling figures. Format and defaults: docs/hal.md.
//
//   {"amplifier":  {"transport": "tcp", "host": "10.0.0.5", "port": 502, "unit": 1},
//    "biometrics": {"transport": "rtu", "device": "/dev/ttyUSB0", "baud": 115200,
//                   "parity": "even", "unit": 2},
//    "comms_timeout_ms": 50}
#pragma once

#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/modbus/poller.hpp"

namespace knoblab::hal {

// A device left out is not polled; at least one is required. Throws
// ConfigError naming the key (prefixed by `where`) for anything the Poller
// would refuse, so a bad file fails at startup, not when the poller starts.
modbus::PollerConfig parse_modbus_config(const nlohmann::json& config, std::string_view where = "modbus");

}  // namespace knoblab::hal
