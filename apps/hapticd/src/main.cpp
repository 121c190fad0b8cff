// hapticd: the realtime task. Reads its backends from a JSON config or flags,
// runs the loop until SIGTERM/SIGINT (or --cycles), then leaves the motor safe.
//
//   hapticd --backend sim --knob moderate-detents --db /var/lib/knoblab/lab.sqlite
//           --socket /run/knoblab/hapticd.sock
//   hapticd --backend sim --rate 10000 --cycles 200000 --free-run --stats-json bench.json
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hapticd/calibration_file.hpp"
#include "knoblab/hal/factory.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hal/modbus_config.hpp"
#include "knoblab/control/schema.hpp"
#include "knoblab/hapticd/control_handler.hpp"
#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/hapticd/model_file.hpp"
#include "knoblab/rt/stats_json.hpp"
#include "knoblab/rt/timing_stats.hpp"

namespace {

using knoblab::hapticd::Daemon;
using nlohmann::json;

std::atomic<Daemon*> g_daemon{nullptr};

void on_signal(int) {
  if (Daemon* d = g_daemon.load()) d->stop();
}

const char* kUsage =
    "usage: hapticd [OPTIONS]\n"
    "  --config FILE        JSON: {\"daq\": {...}, \"lines\": {...}, \"modbus\": {...}} (docs/hal.md);\n"
    "                       any other top-level key is an error\n"
    "  --backend sim|comedi DAQ backend (default sim); --daq-config FILE for comedi\n"
    "  --knob PRESET        sim: the simulated knob (default moderate-detents)\n"
    "  --lines memory|gpiod digital lines (default memory); --lines-config FILE for gpiod\n"
    "  --allow-memory-lines let a real DAQ (comedi) run with in-memory lines: no e-stop\n"
    "                       input, no amplifier-enable line (bench tests only)\n"
    "  --rate HZ            loop rate, 1..20000 (default 10000)\n"
    "  --priority N --cpu N SCHED_FIFO priority (default 80), CPU to pin to\n"
    "  --socket PATH        control socket (docs/protocol.md); --group NAME owns it\n"
    "  --db FILE            store for captures and biometrics\n"
    "  --telemetry NAME     shared-memory telemetry ring, e.g. /knoblab-telemetry\n"
    "  --modbus HOST:PORT   amplifier + biometrics box over Modbus TCP\n"
    "  --cycles N           stop after N cycles\n"
    "  --max-overruns N     overruns in a row that latch the overruns fault (default 10;\n"
    "                       raise it only on a host that is not realtime, e.g. for tests)\n"
    "  --model FILE         model to render from the start (knoblab fit --render-model,\n"
    "                       knoblab discrepancy --model-out)\n"
    "  --calibration FILE   sensor constants to start with, where accept_calibration\n"
    "                       saves them (created on the first accept; docs/protocol.md)\n"
    "  --free-run           run cycles back to back (benchmark); renders a model with\n"
    "                       detents, damping and virtual-mass inertia\n"
    "  --stats-json FILE    write the loop's timing figures as JSON at exit\n"
    "exit status: 0 stopped cleanly, 1 a runtime failure, 2 bad options or configuration\n";

// Bad options or configuration: exit status 2, as for the HAL's ConfigError.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct Options {
  json daq = {{"backend", "sim"}, {"knob", "moderate-detents"}};
  json lines = {{"backend", "memory"}, {"estop", "released"}};
  bool allow_memory_lines = false;
  bool calibration_loaded = false;  // from --calibration: the sim's own constants do not apply
  knoblab::hapticd::DaemonConfig cfg;
  std::string stats_json;
};

std::string need(const std::vector<std::string>& a, std::size_t& i) {
  if (i + 1 >= a.size()) throw UsageError(a[i] + " needs a value");
  return a[++i];
}

// A number option, whole and in range: std::stod would take "1000abc" as 1000
// and a port of 99999 would wrap to 34463 in a uint16_t.
double number_option(const std::string& key, const std::string& text, double lo, double hi) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw UsageError(key + " wants a number, got '" + text + "'");
  if (!(v >= lo && v <= hi)) {
    char range[64];
    std::snprintf(range, sizeof range, "%g … %g", lo, hi);
    throw UsageError(key + " must be in " + range + ", got " + text);
  }
  return v;
}

long long integer_option(const std::string& key, const std::string& text, long long lo, long long hi) {
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) throw UsageError(key + " wants an integer, got '" + text + "'");
  if (v < lo || v > hi)
    throw UsageError(key + " must be in " + std::to_string(lo) + " … " + std::to_string(hi) + ", got " + text);
  return v;
}

// The --config file: each section goes to the part that owns it; a key no
// part owns is a mistake (a typo such as "modbs" would otherwise leave the
// amplifier unsupervised without a word).
void read_config_file(const std::string& path, Options& o) {
  const json c = knoblab::hal::load_config_file(path);
  if (!c.is_object()) throw knoblab::hal::ConfigError(path + ": expected a JSON object");
  for (const auto& [key, value] : c.items()) {
    if (key == "daq") o.daq = value;
    else if (key == "lines") o.lines = value;
    else if (key == "modbus") o.cfg.modbus = knoblab::hal::parse_modbus_config(value, "modbus");
    else
      throw knoblab::hal::ConfigError(path + ": unknown top-level key \"" + key +
                                      "\" (known: daq, lines, modbus)");
  }
}

// A real DAQ drives a real motor: without real lines there is no e-stop
// input and the amplifier-enable output goes nowhere.
void check_lines_for_a_real_daq(const Options& o) {
  if (o.daq.value("backend", "") == "sim" || o.allow_memory_lines) return;
  if (o.lines.value("backend", "") != "memory") return;
  throw UsageError("the " + o.daq.value("backend", std::string("?")) +
                   " DAQ drives a real motor, but the digital lines are in memory: no e-stop input "
                   "would be read and the amplifier-enable line would go nowhere. Configure "
                   "\"lines\": {\"backend\": \"gpiod\", ...} (docs/hal.md), or pass "
                   "--allow-memory-lines for a bench test without them");
}

// A model file (`knoblab fit --render-model`, `knoblab discrepancy
// --model-out`) as load_model's arguments, checked by the same protocol
// schema a client's load_model is.
knoblab::hapticd::RenderParams read_model_file(const std::string& path) {
  json args;
  try {
    args = knoblab::hapticd::read_model_file_args(path);
  } catch (const knoblab::hapticd::ModelFileError& e) {
    throw UsageError(std::string("--model ") + e.what());
  }
  const auto& spec = knoblab::control::command_spec(knoblab::control::Command::load_model);
  if (auto problem = knoblab::control::validate_args(args, spec.args))
    throw UsageError("--model " + path + ": " + problem->key + " " + problem->problem);
  return knoblab::hapticd::render_params_from_args(args, {}, false);
}

Options parse(const std::vector<std::string>& a) {
  Options o;
  o.cfg.loop.priority = 80;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string& k = a[i];
    if (k == "--help" || k == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (k == "--config") {
      read_config_file(need(a, i), o);
    } else if (k == "--allow-memory-lines") {
      o.allow_memory_lines = true;
    } else if (k == "--backend") {
      o.daq["backend"] = need(a, i);
    } else if (k == "--daq-config") {
      o.daq = knoblab::hal::load_config_file(need(a, i));
    } else if (k == "--knob") {
      o.daq["knob"] = need(a, i);
    } else if (k == "--lines") {
      o.lines = {{"backend", need(a, i)}};
    } else if (k == "--lines-config") {
      o.lines = knoblab::hal::load_config_file(need(a, i));
    } else if (k == "--rate") {
      o.cfg.core.rate_hz = number_option(k, need(a, i), 1.0, 20000.0);
    } else if (k == "--priority") {
      o.cfg.loop.priority = static_cast<int>(integer_option(k, need(a, i), 1, 99));
    } else if (k == "--cpu") {
      o.cfg.loop.cpu = static_cast<int>(integer_option(k, need(a, i), -1, 4095));
    } else if (k == "--socket") {
      o.cfg.socket_path = need(a, i);
    } else if (k == "--group") {
      o.cfg.socket_group = need(a, i);
    } else if (k == "--db") {
      o.cfg.db = need(a, i);
    } else if (k == "--telemetry") {
      o.cfg.telemetry_shm = need(a, i);
    } else if (k == "--modbus") {
      const std::string hp = need(a, i);
      const auto colon = hp.rfind(':');
      if (colon == std::string::npos || colon == 0) throw UsageError("--modbus wants HOST:PORT, got '" + hp + "'");
      const auto port = static_cast<std::uint16_t>(integer_option("--modbus's port", hp.substr(colon + 1), 1, 65535));
      knoblab::modbus::PollerConfig pc;
      for (auto* e : {&pc.amplifier, &pc.biometrics}) {
        e->host = hp.substr(0, colon);
        e->port = port;
      }
      o.cfg.modbus = pc;
    } else if (k == "--max-overruns") {
      o.cfg.core.limits.max_consecutive_overruns =
          static_cast<int>(integer_option(k, need(a, i), 1, std::numeric_limits<int>::max()));
    } else if (k == "--cycles") {
      o.cfg.loop.max_cycles = integer_option(k, need(a, i), 1, std::numeric_limits<long long>::max());
    } else if (k == "--model") {
      o.cfg.initial_model = read_model_file(need(a, i));
    } else if (k == "--calibration") {
      o.cfg.calibration_file = need(a, i);
      if (std::filesystem::exists(o.cfg.calibration_file)) {
        try {
          const auto file = knoblab::hapticd::read_calibration_file(o.cfg.calibration_file);
          o.cfg.core.calibration = file.constants;
          o.cfg.accepted_calibrations = file.accepted;
          o.calibration_loaded = true;
        } catch (const std::runtime_error& e) {
          throw UsageError(std::string("--calibration: ") + e.what());
        }
      }
    } else if (k == "--free-run") {
      o.cfg.loop.free_run = true;
    } else if (k == "--stats-json") {
      o.stats_json = need(a, i);
    } else {
      throw UsageError("unknown option " + k + " (see --help)");
    }
  }
  if (o.daq.value("backend", "") == "sim") o.daq["rate_hz"] = o.cfg.core.rate_hz;
  o.cfg.knob = o.daq.value("knob", "");
  if (o.daq.value("backend", "") == "sim" && o.daq.contains("hand") && o.daq["hand"].is_object() &&
      o.daq["hand"].contains("channel") && o.daq["hand"]["channel"].is_string())
    o.cfg.hand_channel = o.daq["hand"]["channel"].get<std::string>();
  check_lines_for_a_real_daq(o);
  if (o.cfg.initial_model)
    if (const auto p = knoblab::hapticd::render_params_problem(*o.cfg.initial_model, o.cfg.core.limits))
      throw UsageError("--model: " + p->message);
  return o;
}

// The benchmark's model: the moderate-detents knob as the renderer sees it.
void render_benchmark_model(Daemon& d) {
  knoblab::hapticd::CoreCommand c;
  c.kind = knoblab::hapticd::CoreCommand::SetRender;
  c.immediate = true;
  c.render.M_acc = 0.049e-3;
  c.render.B_vel = 0.52e-3;
  c.render.A_pos = 11e-3;
  c.render.P_pos = 1.0 / 12.0;
  d.post(c);
  c.kind = knoblab::hapticd::CoreCommand::SetMode;
  c.mode = knoblab::hapticd::Mode::Render;
  d.post(c);
}

json stats_json(const knoblab::rt::LoopResult& r, const knoblab::hapticd::DaemonConfig& cfg, std::uint64_t dropped) {
  const auto s = knoblab::rt::summarize(r.stats);
  json j;
  j["cycles"] = s.cycles;
  j["rate_hz"] = cfg.core.rate_hz;
  j["free_run"] = cfg.loop.free_run;
  j["cycle_cost_ns"] = {{"median", s.compute.median_ns}, {"p99", s.compute.p99_ns},
                        {"p999", s.compute.p999_ns}, {"max", s.compute.max_ns}, {"mean", s.compute.mean_ns}};
  if (!cfg.loop.free_run)
    j["wakeup_latency_ns"] = {{"median", s.wakeup.median_ns}, {"p99", s.wakeup.p99_ns},
                              {"p999", s.wakeup.p999_ns}, {"max", s.wakeup.max_ns}};
  j["overruns"] = s.overruns;
  j["ring_dropped"] = dropped;
  j["realtime"] = r.realtime;
  j["backend"] = knoblab::rt::backend_name();
  j["stop_reason"] = knoblab::rt::to_string(r.stop_reason);
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const knoblab::hal::ConfigError& e) {
    std::cerr << "hapticd: " << e.what() << "\n";
    return 2;
  } catch (const UsageError& e) {
    std::cerr << "hapticd: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // e.g. std::stoi on "--rate fast"
    std::cerr << "hapticd: bad option: " << e.what() << "\n";
    return 2;
  }
  try {
    auto daq = knoblab::hal::make_daq(o.daq, "daq");
    if (auto* sim = dynamic_cast<knoblab::capture::SimDaq*>(daq.get()); sim && !o.calibration_loaded)
      o.cfg.core.calibration = sim->calibration();
    auto lines = knoblab::hal::make_lines(o.lines, "lines");
    Daemon daemon(o.cfg, std::move(daq), std::move(lines));
    if (o.cfg.loop.free_run) render_benchmark_model(daemon);
    g_daemon.store(&daemon);
    std::signal(SIGTERM, on_signal);
    std::signal(SIGINT, on_signal);
    const knoblab::rt::LoopResult r = daemon.run();
    g_daemon.store(nullptr);
    for (const auto& w : r.warnings) std::cerr << "hapticd: warning: " << w << "\n";
    const json stats = stats_json(r, o.cfg, daemon.ring_dropped());
    if (!o.stats_json.empty()) {
      std::ofstream f(o.stats_json);
      f << stats.dump(2) << "\n";
      if (!f) throw std::runtime_error("cannot write " + o.stats_json);
    }
    std::cout << stats.dump() << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "hapticd: error: " << e.what() << "\n";
    return 1;
  }
}
