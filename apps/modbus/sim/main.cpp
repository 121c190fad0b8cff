// knoblab-modbus-sim: the servo amplifier and the biometrics box as one
// Modbus TCP server, for developing and testing hapticd without hardware.
// Prints "listening ADDRESS:PORT" once it accepts connections.
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>
#include <string_view>
#include <thread>

#include "knoblab/modbus/sim_server.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

constexpr const char* kUsage = R"(usage: knoblab-modbus-sim [options]
  --port N          TCP port (default 1502; 0 = ephemeral, printed on stdout)
  --bind ADDR       IPv4 address to listen on (default 127.0.0.1)
  --seed N          signal seed (default 1)
  --duration S      exit after S seconds (default: run until SIGINT/SIGTERM)
  --amp-unit N      amplifier unit id (default 1)
  --bio-unit N      biometrics unit id (default 2)
  --control-unit N  simulator control unit id (default 247)
  --fault SPEC      scheduled fault, repeatable:
                      disconnect-after=S[:REFUSE_MS]
                      exception=CODE[:amp|bio][@S]
                      stale-after=S[:bio|amp|all]
                      amp-fault-after=S:BITS
                      slow=MS[:amp|bio][@S]
                      hang-after=S[:bio|amp|all]
Register maps and the control block: docs/modbus.md.
)";

template <typename T>
bool parse(std::string_view s, T& out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc{} && end == s.data() + s.size();
}

int usage_error(const std::string& message) {
  std::cerr << "knoblab-modbus-sim: " << message << "\n" << kUsage;
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  knoblab::modbus::SimConfig config;
  config.port = 1502;  // 502 needs root
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return 0;
    }
    if (i + 1 >= argc) return usage_error("missing value for " + std::string(arg));
    const std::string_view value = argv[++i];
    bool ok = true;
    if (arg == "--port") {
      ok = parse(value, config.port);
    } else if (arg == "--bind") {
      config.bind = std::string(value);
    } else if (arg == "--seed") {
      ok = parse(value, config.seed);
    } else if (arg == "--duration") {
      double seconds = 0.0;
      ok = parse(value, seconds) && seconds >= 0.0;
      config.duration = std::chrono::milliseconds(static_cast<long long>(seconds * 1000.0));
    } else if (arg == "--amp-unit") {
      ok = parse(value, config.amplifier_unit);
    } else if (arg == "--bio-unit") {
      ok = parse(value, config.biometrics_unit);
    } else if (arg == "--control-unit") {
      ok = parse(value, config.control_unit);
    } else if (arg == "--fault") {
      std::string error;
      auto fault = knoblab::modbus::parse_fault(value, &error);
      if (!fault) return usage_error(error);
      config.faults.push_back(*fault);
    } else {
      return usage_error("unknown option " + std::string(arg));
    }
    if (!ok) return usage_error("bad value for " + std::string(arg) + ": " + std::string(value));
  }

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);

  knoblab::modbus::SimServer server(config);
  std::string error;
  if (!server.start(&error)) {
    std::cerr << error << "\n";
    return 1;
  }
  std::cout << "listening " << config.bind << ":" << server.port() << std::endl;
  while (g_stop == 0 && server.running()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  server.stop();
  return 0;
}
