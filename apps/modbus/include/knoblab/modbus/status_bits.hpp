// The status word the poller publishes for the realtime loop: one
// std::atomic<std::uint32_t>, read lock-free each cycle (Poller::status()).
// Bits 0..7 are problems; bits 8.. are plain state.
#pragma once

#include <cstdint>
#include <string>

namespace knoblab::modbus::status {

inline constexpr std::uint32_t kAmpFault = 1u << 0;             // amp reports a fault (fault word != 0)
inline constexpr std::uint32_t kAmpCommsLost = 1u << 1;         // no fresh amp read within comms_timeout
inline constexpr std::uint32_t kAmpDisabledUnexpectedly = 1u << 2;  // we enabled it, it reports disabled
inline constexpr std::uint32_t kBiometricsLost = 1u << 3;       // no biometrics read within biometrics_timeout
inline constexpr std::uint32_t kBiometricsStale = 1u << 4;      // counter still for > stale_periods samples
inline constexpr std::uint32_t kAmpException = 1u << 5;         // last amp request got a Modbus exception
inline constexpr std::uint32_t kBiometricsException = 1u << 6;  // last biometrics request got one
inline constexpr std::uint32_t kDeviceMismatch = 1u << 7;       // wrong map version or device type at a unit id

inline constexpr std::uint32_t kAmpEnabled = 1u << 8;  // amp reports its output stage on
inline constexpr std::uint32_t kRunning = 1u << 9;     // the poller thread is running

inline constexpr std::uint32_t kProblemMask = 0xFFu;
// What should stop torque output: the amplifier cannot be trusted to be
// doing what the loop thinks.
inline constexpr std::uint32_t kAmpTripMask =
    kAmpFault | kAmpCommsLost | kAmpDisabledUnexpectedly | kDeviceMismatch;

// "amp-fault|amp-comms-lost" style, for logs ("ok" if no bit is set).
std::string describe(std::uint32_t word);

}  // namespace knoblab::modbus::status
