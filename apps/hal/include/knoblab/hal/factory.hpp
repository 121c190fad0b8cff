// Backends from configuration, so hapticd picks hardware or simulation by
// editing a file, not by recompiling:
//   {"backend": "sim" | "comedi", …}   → capture::Daq
//   {"backend": "gpiod" | "memory", …} → DigitalLines
// Every error is a ConfigError naming the key (prefixed by `where`), or the
// backend's own std::runtime_error naming the device or line. docs/hal.md.
#pragma once

#include <filesystem>
#include <memory>
#include <string_view>

#include <nlohmann/json.hpp>

#include "knoblab/capture/daq.hpp"
#include "knoblab/hal/comedi_api.hpp"
#include "knoblab/hal/config_error.hpp"
#include "knoblab/hal/digital_lines.hpp"

namespace knoblab::hal {

// Sim: {"backend": "sim", "knob": "<preset id>", "rate_hz": 10000, "seed": 1}
// → a capture::SimDaq (dynamic_cast it for calibration()). rate_hz (default
// 10 kHz) must equal the loop's rate: the plant steps 1/rate_hz per read().
std::unique_ptr<capture::Daq> make_daq(const nlohmann::json& config, std::string_view where = "daq",
                                       ComediApi& comedi = system_comedi_api());

// Memory: {"backend": "memory", "estop": "asserted" | "released"} → MemoryLines.
std::unique_ptr<DigitalLines> make_lines(const nlohmann::json& config, std::string_view where = "lines");

// JSON text → json; a syntax error becomes a ConfigError naming `origin`.
nlohmann::json parse_config_text(std::string_view text, std::string_view origin);
nlohmann::json load_config_file(const std::filesystem::path& path);

}  // namespace knoblab::hal
