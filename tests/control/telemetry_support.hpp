// Telemetry test helpers: unique shm names and samples whose every field is
// derived from one counter, so a torn record is recognisable.
#pragma once

#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <string>

#include "knoblab/control/telemetry_sample.hpp"

namespace knoblab::control::test {

inline std::string unique_shm_name(const char* what) {
  static std::atomic<int> counter{0};
  return "/knoblab-test-" + std::string(what) + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

inline TelemetrySample counter_sample(std::uint64_t i) {
  const double x = static_cast<double>(i);
  return {x, 2 * x, 3 * x, x, -x, static_cast<std::uint32_t>(i % 4), static_cast<std::uint32_t>(i & 0xFFFF)};
}

// True if `r` is exactly what counter samples produce for the window ending
// at sample r.t with `decimation` samples per window.
inline bool consistent(const TelemetryRecord& r, std::uint32_t decimation) {
  const auto i = static_cast<std::uint64_t>(r.t);
  std::uint32_t faults = 0;
  for (std::uint64_t j = i + 1 - decimation; j <= i; ++j) faults |= static_cast<std::uint32_t>(j & 0xFFFF);
  return r.t == static_cast<double>(i) && r.theta == 2 * r.t && r.omega == 3 * r.t && r.torque == r.t &&
         r.command == -r.t && r.torque_max == r.t && r.torque_min == r.t - (decimation - 1) &&
         r.mode == i % 4 && r.fault_bits == faults && (i + 1) % decimation == 0;
}

}  // namespace knoblab::control::test
