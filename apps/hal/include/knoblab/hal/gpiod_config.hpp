// Configuration of the libgpiod backend: which chip, and each role's line
// found BY NAME (never by offset), with its electrical settings.
//
//   {"backend": "gpiod", "chip": "/dev/gpiochip0" | "auto",
//    "lines": {"amp_enable": "AMP_EN", "estop": "ESTOP_N",
//              "capture_button": "FOOTSW", "status_led": "LED_STATUS"}}
//
// A line may also be an object overriding its role's defaults:
//   {"name": "ESTOP_N", "active_low": true, "bias": "pull-down", "debounce_us": 0}
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/hal/digital_lines.hpp"

namespace knoblab::hal {

enum class Bias { AsIs, Disabled, PullUp, PullDown };

struct LineSpec {
  std::string name{};      // as the chip exposes it (see `gpioinfo`)
  bool active_low = false;
  Bias bias = Bias::AsIs;
  std::uint32_t debounce_us = 0;
};

// Role defaults. ESTOP_N is active low (physical low = e-stop), so it is
// pulled DOWN: an open circuit (pulled cable) reads low = e-stop asserted.
// The footswitch is a contact to ground: pulled up, active low, debounced.
LineSpec default_line_spec(LineRole role);

struct GpiodLinesConfig {
  std::string chip = "auto";                  // "/dev/gpiochipN", or "auto": search every chip
  std::filesystem::path device_dir = "/dev";  // where "auto" looks for gpiochip*
  std::string consumer = "hapticd";           // shown by `gpioinfo` as the user
  LineSpec amp_enable = default_line_spec(LineRole::AmpEnable);
  LineSpec estop = default_line_spec(LineRole::Estop);
  LineSpec capture_button = default_line_spec(LineRole::CaptureButton);
  LineSpec status_led = default_line_spec(LineRole::StatusLed);

  const LineSpec& line(LineRole role) const;
  LineSpec& line(LineRole role);
};

// Throws ConfigError naming the key (prefixed by `where`).
GpiodLinesConfig parse_gpiod_config(const nlohmann::json& config, std::string_view where = "lines");

std::string_view bias_name(Bias bias);

}  // namespace knoblab::hal
