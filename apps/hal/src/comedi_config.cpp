#include "knoblab/hal/comedi_config.hpp"

#include <array>
#include <utility>

#include "knoblab/hal/config_reader.hpp"
#include "knoblab/hal/config_error.hpp"

namespace knoblab::hal {

namespace {

using detail::ConfigReader;

constexpr std::array<std::pair<Aref, std::string_view>, 4> kArefNames = {{
    {Aref::Ground, "ground"},
    {Aref::Common, "common"},
    {Aref::Diff, "diff"},
    {Aref::Other, "other"},
}};

Aref parse_aref(ConfigReader& r) {
  if (!r.has("aref")) return Aref::Ground;
  const std::string text = r.string("aref");
  for (const auto& [aref, name] : kArefNames)
    if (text == name) return aref;
  r.fail("aref", "unknown reference \"" + text + "\" (use ground, common, diff or other)");
}

// "range": index, or "range_V": [min, max] — not both.
void parse_range(ConfigReader& r, AnalogChannelConfig& c) {
  c.range = r.optional_uint("range");
  if (const nlohmann::json* v = r.find("range_V")) {
    const std::string path = r.path_of("range_V");
    if (!v->is_array() || v->size() != 2) throw ConfigError(path + ": expected [min_V, max_V], got " + v->dump());
    const VoltRange range{detail::as_number((*v)[0], path + "[0]"), detail::as_number((*v)[1], path + "[1]")};
    if (!(range.min_V < range.max_V)) throw ConfigError(path + ": min must be below max, got " + v->dump());
    if (c.range) throw ConfigError(path + ": give either \"range\" (index) or \"range_V\", not both");
    c.range_V = range;
  }
}

AnalogChannelConfig parse_analog(ConfigReader& parent, std::string_view key, bool input) {
  ConfigReader r = parent.object(key);
  AnalogChannelConfig c;
  c.subdevice = r.optional_uint("subdevice");
  c.channel = r.uint("channel");
  parse_range(r, c);
  c.aref = parse_aref(r);
  c.gain = r.number_or("gain", 1.0);
  if (c.gain == 0.0) r.fail("gain", "must not be 0");
  if (input) c.offset_V = r.number_or("offset_V", 0.0);
  r.finish();
  return c;
}

CounterConfig parse_counter(ConfigReader& parent) {
  ConfigReader r = parent.object("encoder");
  CounterConfig c;
  c.device = r.string_or("device", "");
  c.subdevice = r.optional_uint("subdevice");
  c.channel = r.uint("channel");
  c.reset_on_open = r.boolean_or("reset_on_open", false);
  const double sign = r.number_or("sign", 1.0);
  if (sign != 1.0 && sign != -1.0) r.fail("sign", "must be 1 or -1");
  c.sign = sign > 0 ? 1 : -1;
  r.finish();
  return c;
}

}  // namespace

ComediDaqConfig parse_comedi_config(const nlohmann::json& config, std::string_view where) {
  ConfigReader r(config, std::string(where));
  ComediDaqConfig c;
  r.has("backend");  // chosen by the factory; allowed here
  c.device = r.string("device");
  if (c.device.empty()) r.fail("device", "must be a device path such as /dev/comedi0");
  c.torque = parse_analog(r, "torque", true);
  c.accel = parse_analog(r, "accel", true);
  c.motor = parse_analog(r, "motor", false);
  c.encoder = parse_counter(r);
  r.finish();
  return c;
}

}  // namespace knoblab::hal
