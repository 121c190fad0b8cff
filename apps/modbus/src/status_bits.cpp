#include "knoblab/modbus/status_bits.hpp"

#include <array>
#include <utility>

namespace knoblab::modbus::status {

std::string describe(std::uint32_t word) {
  static constexpr std::array<std::pair<std::uint32_t, const char*>, 11> names{{
      {kAmpFault, "amp-fault"},
      {kAmpCommsLost, "amp-comms-lost"},
      {kAmpDisabledUnexpectedly, "amp-disabled-unexpectedly"},
      {kBiometricsLost, "biometrics-lost"},
      {kBiometricsStale, "biometrics-stale"},
      {kAmpException, "amp-exception"},
      {kBiometricsException, "biometrics-exception"},
      {kAmpMismatch, "amp-mismatch"},
      {kBiometricsMismatch, "biometrics-mismatch"},
      {kAmpEnabled, "amp-enabled"},
      {kRunning, "running"},
  }};
  std::string out;
  for (const auto& [bit, name] : names) {
    if ((word & bit) == 0) continue;
    if (!out.empty()) out += '|';
    out += name;
  }
  return out.empty() ? "ok" : out;
}

}  // namespace knoblab::modbus::status
