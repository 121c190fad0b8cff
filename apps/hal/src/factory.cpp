#include "knoblab/hal/factory.hpp"

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "knoblab/hal/config_reader.hpp"
#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hal/comedi_daq.hpp"
#include "knoblab/hal/gpiod_lines.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hal/shared_hand_channel.hpp"
#include "knoblab/jsonread/nesting.hpp"
#include "knoblab/sim/hand.hpp"
#include "knoblab/sim/presets.hpp"

namespace knoblab::hal {

namespace {

using detail::ConfigReader;

std::string backend_of(const nlohmann::json& config, const std::string& where) {
  ConfigReader r(config, where);
  return r.string("backend");
}

[[noreturn]] void unknown_backend(const std::string& where, const std::string& name, const char* choices) {
  throw ConfigError(where + ".backend: unknown backend \"" + name + "\" (use " + choices + ")");
}

std::unique_ptr<capture::Daq> make_sim_daq(const nlohmann::json& config, const std::string& where) {
  ConfigReader r(config, where);
  r.has("backend");
  const std::string knob = r.string("knob");
  const sim::presets::Preset* preset = sim::presets::find(knob);
  if (preset == nullptr) {
    std::string ids;
    for (const auto& p : sim::presets::list()) ids += (ids.empty() ? "" : ", ") + std::string(p.id);
    r.fail("knob", "unknown knob preset \"" + knob + "\" (presets: " + ids + ")");
  }
  // Must equal the loop's rate: the plant steps 1/rate_hz per read().
  const double rate_hz = r.number_or("rate_hz", 10000.0);
  if (!(rate_hz >= 1.0 && rate_hz <= 100000.0)) r.fail("rate_hz", "must be in [1, 100000] Hz");
  sim::PlantConfig plant;
  plant.knob = preset->knob;
  plant.seed = r.uint64_or("seed", plant.seed);
  std::optional<sim::HandParams> hand;
  std::optional<SharedHandChannel> guided;
  if (r.has("hand") && r.object("hand").has("channel")) {  // a simulated participant steers it
    ConfigReader h = r.object("hand");
    const std::string name = h.string("channel");
    h.finish();
    try {
      guided.emplace(name);
    } catch (const std::runtime_error& e) {
      h.fail("channel", e.what());
    }
  } else if (r.has("hand")) {  // someone turning the knob, for render mode
    ConfigReader h = r.object("hand");
    hand.emplace();
    hand->amplitude_rad = h.number_or("amplitude_rad", hand->amplitude_rad);
    hand->frequency_hz = h.number_or("frequency_hz", hand->frequency_hz);
    hand->stiffness = h.number_or("stiffness", hand->stiffness);
    hand->damping = h.number_or("damping", hand->damping);
    if (!(std::abs(hand->amplitude_rad) <= 100.0)) h.fail("amplitude_rad", "must be within ±100 rad");
    if (!(hand->frequency_hz >= 0.0 && hand->frequency_hz <= 100.0)) h.fail("frequency_hz", "must be in [0, 100] Hz");
    if (!(hand->stiffness >= 0.0 && hand->stiffness <= 100.0)) h.fail("stiffness", "must be in [0, 100] N·m/rad");
    if (!(hand->damping >= 0.0 && hand->damping <= 10.0)) h.fail("damping", "must be in [0, 10] N·m·s/rad");
    h.finish();
  }
  r.finish();
  auto daq = std::make_unique<capture::SimDaq>(plant, rate_hz);
  if (hand) daq->plant().add_effect(sim::make_hand(*hand));
  if (guided) daq->plant().add_effect(sim::make_guided_hand(guided->channel(), guided->mapping()));
  return daq;
}

std::unique_ptr<DigitalLines> make_memory_lines(const nlohmann::json& config, const std::string& where) {
  ConfigReader r(config, where);
  r.has("backend");
  const std::string estop = r.string_or("estop", "asserted");
  if (estop != "asserted" && estop != "released")
    r.fail("estop", "must be \"asserted\" or \"released\", got \"" + estop + "\"");
  r.finish();
  return std::make_unique<MemoryLines>(estop == "asserted");
}

}  // namespace

std::unique_ptr<capture::Daq> make_daq(const nlohmann::json& config, std::string_view where_view, ComediApi& comedi) {
  const std::string where(where_view);
  const std::string backend = backend_of(config, where);
  if (backend == "sim") return make_sim_daq(config, where);
  if (backend == "comedi") return std::make_unique<ComediDaq>(parse_comedi_config(config, where), comedi);
  unknown_backend(where, backend, "sim or comedi");
}

std::unique_ptr<DigitalLines> make_lines(const nlohmann::json& config, std::string_view where_view) {
  const std::string where(where_view);
  const std::string backend = backend_of(config, where);
  if (backend == "memory") return make_memory_lines(config, where);
  if (backend == "gpiod") return std::make_unique<GpiodLines>(parse_gpiod_config(config, where));
  unknown_backend(where, backend, "gpiod or memory");
}

nlohmann::json parse_config_text(std::string_view text, std::string_view origin) {
  if (const auto deep = jsonread::nesting_problem(text))
    throw ConfigError(std::string(origin) + ": invalid JSON: " + *deep);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line 3, column 5: …"
    std::string why = e.what();
    if (const auto at = why.find("] "); at != std::string::npos) why.erase(0, at + 2);
    throw ConfigError(std::string(origin) + ": invalid JSON: " + why);
  }
}

nlohmann::json load_config_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path.string() + ": cannot read the configuration file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_config_text(text.str(), path.string());
}

}  // namespace knoblab::hal
