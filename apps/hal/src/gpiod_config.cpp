#include "knoblab/hal/gpiod_config.hpp"

#include <array>
#include <utility>

#include "knoblab/hal/config_reader.hpp"
#include "knoblab/hal/config_error.hpp"

namespace knoblab::hal {

namespace {

constexpr std::array<std::pair<Bias, std::string_view>, 4> kBiasNames = {{
    {Bias::AsIs, "as-is"},
    {Bias::Disabled, "disabled"},
    {Bias::PullUp, "pull-up"},
    {Bias::PullDown, "pull-down"},
}};

Bias parse_bias(const std::string& text, const std::string& path) {
  for (const auto& [bias, name] : kBiasNames)
    if (text == name) return bias;
  throw ConfigError(path + ": unknown bias \"" + text + "\" (use as-is, disabled, pull-up or pull-down)");
}

// A line is its name, or an object overriding the role's defaults.
LineSpec parse_line(const nlohmann::json& v, const std::string& path, LineRole role) {
  LineSpec spec = default_line_spec(role);
  if (v.is_string()) {
    spec.name = v.get<std::string>();
  } else {
    detail::ConfigReader r(v, path);
    spec.name = r.string("name");
    spec.active_low = r.boolean_or("active_low", spec.active_low);
    if (r.has("bias")) spec.bias = parse_bias(r.string("bias"), r.path_of("bias"));
    const std::uint64_t debounce = r.uint64_or("debounce_us", spec.debounce_us);
    if (debounce > 1'000'000) r.fail("debounce_us", "must be at most 1000000 (1 s)");
    spec.debounce_us = static_cast<std::uint32_t>(debounce);
    r.finish();
  }
  if (spec.name.empty()) throw ConfigError(path + ": line name is empty");
  return spec;
}

}  // namespace

std::string_view bias_name(Bias bias) {
  for (const auto& [b, name] : kBiasNames)
    if (b == bias) return name;
  return "?";
}

LineSpec default_line_spec(LineRole role) {
  switch (role) {
    case LineRole::AmpEnable: return {"AMP_EN", false, Bias::AsIs, 0};
    case LineRole::Estop: return {"ESTOP_N", true, Bias::PullDown, 0};
    case LineRole::CaptureButton: return {"FOOTSW", true, Bias::PullUp, 5000};
    case LineRole::StatusLed: return {"LED_STATUS", false, Bias::AsIs, 0};
  }
  return {};
}

const LineSpec& GpiodLinesConfig::line(LineRole role) const {
  switch (role) {
    case LineRole::AmpEnable: return amp_enable;
    case LineRole::Estop: return estop;
    case LineRole::CaptureButton: return capture_button;
    case LineRole::StatusLed: break;
  }
  return status_led;
}

LineSpec& GpiodLinesConfig::line(LineRole role) {
  return const_cast<LineSpec&>(std::as_const(*this).line(role));
}

GpiodLinesConfig parse_gpiod_config(const nlohmann::json& config, std::string_view where) {
  detail::ConfigReader r(config, std::string(where));
  GpiodLinesConfig c;
  r.has("backend");  // chosen by the factory; allowed here
  c.chip = r.string("chip");
  if (c.chip.empty()) r.fail("chip", "must be a /dev/gpiochipN path or \"auto\"");
  c.device_dir = r.string_or("device_dir", c.device_dir.string());
  c.consumer = r.string_or("consumer", c.consumer);
  detail::ConfigReader lines = r.object("lines");
  for (LineRole role : kLineRoles) c.line(role) = parse_line(lines.value(role_key(role)), lines.path_of(role_key(role)), role);
  lines.finish();
  r.finish();
  for (LineRole a : kLineRoles)
    for (LineRole b : kLineRoles)
      if (a < b && c.line(a).name == c.line(b).name)
        throw ConfigError(lines.path() + ": " + std::string(role_key(a)) + " and " + std::string(role_key(b)) +
                          " both name line \"" + c.line(a).name + "\"");
  return c;
}

}  // namespace knoblab::hal
