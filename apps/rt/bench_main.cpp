// knoblab-rt-bench: cyclictest-like measurement of the PeriodicLoop itself —
// paced (not free-running) with an empty cycle — printed as one JSON object.
// The full hapticd benchmark with the simulated plant lives with hapticd.
//
//   knoblab-rt-bench [--rate HZ] [--cycles N] [--priority P] [--cpu C]
//                    [--no-mlock] [--require-rt] [--bins]
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <format>
#include <string>
#include <string_view>

#include "knoblab/rt/os.hpp"
#include "knoblab/rt/periodic_loop.hpp"
#include "knoblab/rt/stats_json.hpp"

namespace {

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr,
               "knoblab-rt-bench: %s\nusage: knoblab-rt-bench [--rate HZ] [--cycles N] "
               "[--priority P] [--cpu C] [--no-mlock] [--require-rt] [--bins]\n",
               why);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace knoblab::rt;
  LoopConfig config;
  config.max_cycles = 20000;
  bool bins = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage("missing value");
      return argv[++i];
    };
    if (arg == "--rate") config.rate_hz = std::atof(value());
    else if (arg == "--cycles") config.max_cycles = std::atoll(value());
    else if (arg == "--priority") config.priority = std::atoi(value());
    else if (arg == "--cpu") config.cpu = std::atoi(value());
    else if (arg == "--no-mlock") config.lock_memory = false;
    else if (arg == "--require-rt") config.require_realtime = true;
    else if (arg == "--bins") bins = true;
    else usage("unknown argument");
  }
  if (config.max_cycles < 1) usage("--cycles must be >= 1");

  try {
    std::atomic<bool> stop{false};
    const std::int64_t t0 = now();
    const LoopResult r = run(config, [](const CycleInfo&) {}, stop);
    const double elapsed_s = static_cast<double>(now() - t0) * 1e-9;
    std::string out = "{\"backend\":" + json_string(backend_name());
    out += std::format(",\"rate_hz\":{},\"elapsed_s\":{:.3f}", config.rate_hz, elapsed_s);
    out += ",\"cycles_requested\":" + std::to_string(config.max_cycles);
    out += std::string(",\"realtime\":") + (r.realtime ? "true" : "false");
    out += std::string(",\"memory_locked\":") +
           (config.lock_memory && r.memory_status.ok() ? "true" : "false");
    out += ",\"cpu\":" + std::to_string(config.cpu);
    out += ",\"warnings\":[";
    for (std::size_t i = 0; i < r.warnings.size(); ++i)
      out += (i ? "," : "") + json_string(r.warnings[i]);
    out += "],\"stats\":" + to_json(r.stats, bins) + "}";
    std::puts(out.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "knoblab-rt-bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
