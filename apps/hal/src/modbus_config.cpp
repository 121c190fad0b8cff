#include "knoblab/hal/modbus_config.hpp"

#include <array>
#include <chrono>
#include <limits>
#include <string>
#include <utility>

#include "knoblab/hal/config_reader.hpp"
#include "knoblab/hal/config_error.hpp"
#include "knoblab/modbus/register_map.hpp"

namespace knoblab::hal {

namespace {

using detail::ConfigReader;
using modbus::Millis;

constexpr int kMaxFifoPriority = 99;  // Linux SCHED_FIFO range 1..99

constexpr std::array<std::pair<modbus::Parity, std::string_view>, 3> kParityNames = {{
    {modbus::Parity::none, "none"},
    {modbus::Parity::even, "even"},
    {modbus::Parity::odd, "odd"},
}};

Millis millis_or(ConfigReader& r, std::string_view key, Millis fallback) {
  const std::optional<unsigned> v = r.optional_uint(key);
  return v ? Millis{*v} : fallback;
}

// A small integer setting; range checks beyond "fits" are modbus::validate's.
int small_int_or(ConfigReader& r, std::string_view key, int fallback) {
  const std::optional<unsigned> v = r.optional_uint(key);
  if (!v) return fallback;
  if (*v > 255) r.fail(key, "must be below 256, got " + std::to_string(*v));
  return static_cast<int>(*v);
}

modbus::Parity parse_parity(ConfigReader& r) {
  const std::string text = r.string_or("parity", "none");
  for (const auto& [parity, name] : kParityNames)
    if (text == name) return parity;
  r.fail("parity", "unknown parity \"" + text + "\" (use none, even or odd)");
}

// One device's endpoint; only its transport's keys are known, so a serial
// setting on a TCP device (or the reverse) is rejected as unknown.
modbus::ModbusEndpoint parse_endpoint(ConfigReader& parent, std::string_view key, int default_unit) {
  ConfigReader r = parent.object(key);
  modbus::ModbusEndpoint e;
  const std::string transport = r.string("transport");
  if (transport == "tcp") {
    e.kind = modbus::Transport::tcp;
    e.host = r.string("host");
    if (const std::optional<unsigned> port = r.optional_uint("port")) {
      if (*port < 1 || *port > std::numeric_limits<std::uint16_t>::max())
        r.fail("port", "must be 1..65535, got " + std::to_string(*port));
      e.port = static_cast<std::uint16_t>(*port);
    }
  } else if (transport == "rtu") {
    e.kind = modbus::Transport::rtu;
    e.device = r.string("device");
    if (const std::optional<unsigned> baud = r.optional_uint("baud")) e.baud = *baud;
    e.parity = parse_parity(r);
    e.data_bits = small_int_or(r, "data_bits", e.data_bits);
    e.stop_bits = small_int_or(r, "stop_bits", e.stop_bits);
  } else {
    r.fail("transport", "unknown transport \"" + transport + "\" (use tcp or rtu)");
  }
  e.unit_id = small_int_or(r, "unit", default_unit);
  e.response_timeout = millis_or(r, "response_timeout_ms", e.response_timeout);
  r.finish();
  if (auto problem = modbus::validate(e)) throw ConfigError(r.path() + ": " + *problem);
  return e;
}

// A PollerConfig member path ("amplifier.response_timeout") as the key that
// sets it here ("amplifier.response_timeout_ms").
std::string key_of(const std::string& setting) {
  const auto dot = setting.rfind('.');
  const std::string head = dot == std::string::npos ? "" : setting.substr(0, dot + 1);
  const std::string field = dot == std::string::npos ? setting : setting.substr(dot + 1);
  if (field == "unit_id") return head + "unit";
  if (field.ends_with("_period") || field.ends_with("_timeout")) return head + field + "_ms";
  return setting;
}

}  // namespace

modbus::PollerConfig parse_modbus_config(const nlohmann::json& config, std::string_view where_view) {
  const std::string where(where_view);
  ConfigReader r(config, where);
  modbus::PollerConfig c;
  c.poll_amplifier = r.has("amplifier");
  c.poll_biometrics = r.has("biometrics");
  if (!c.poll_amplifier && !c.poll_biometrics)
    throw ConfigError(where + ": nothing to poll: give \"amplifier\", \"biometrics\" or both");
  if (c.poll_amplifier) c.amplifier = parse_endpoint(r, "amplifier", modbus::kDefaultAmplifierUnit);
  if (c.poll_biometrics) c.biometrics = parse_endpoint(r, "biometrics", modbus::kDefaultBiometricsUnit);
  c.amplifier_period = millis_or(r, "amplifier_period_ms", c.amplifier_period);
  c.biometrics_period = millis_or(r, "biometrics_period_ms", c.biometrics_period);
  c.comms_timeout = millis_or(r, "comms_timeout_ms", c.comms_timeout);
  c.biometrics_timeout = millis_or(r, "biometrics_timeout_ms", c.biometrics_timeout);
  if (const std::optional<unsigned> priority = r.optional_uint("priority")) {
    if (*priority > kMaxFifoPriority)
      r.fail("priority", "must be 0 (hapticd's default) or a SCHED_FIFO priority 1..99, got " +
                             std::to_string(*priority));
    c.priority = static_cast<int>(*priority);
  }
  r.finish();
  // The Poller's own rules, so the file fails here with a path and not
  // later when hapticd builds the poller.
  if (auto problem = modbus::validate(c)) {
    const std::string path = problem->setting.empty() ? where : r.path_of(key_of(problem->setting));
    throw ConfigError(path + ": " + problem->why);
  }
  return c;
}

}  // namespace knoblab::hal
