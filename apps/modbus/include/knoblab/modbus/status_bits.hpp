// The status word the poller publishes for the realtime loop: one
// std::atomic<std::uint32_t>, read lock-free each cycle (Poller::status()).
// Bits 0..7 and 10 are problems (kProblemMask); bits 8 and 9 are plain state.
// Bit 10 came last: the older bits keep their positions for logs and tools.
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
inline constexpr std::uint32_t kAmpMismatch = 1u << 7;          // the amp's unit id answers with another map or device
inline constexpr std::uint32_t kBiometricsMismatch = 1u << 10;  // the box's unit id answers with another map or device

inline constexpr std::uint32_t kAmpEnabled = 1u << 8;  // amp reports its output stage on
inline constexpr std::uint32_t kRunning = 1u << 9;     // the poller is running

inline constexpr std::uint32_t kProblemMask = kAmpFault | kAmpCommsLost | kAmpDisabledUnexpectedly |
                                              kBiometricsLost | kBiometricsStale | kAmpException |
                                              kBiometricsException | kAmpMismatch | kBiometricsMismatch;
// What should stop torque output: the amplifier cannot be trusted to be
// doing what the loop thinks.
inline constexpr std::uint32_t kAmpTripMask =
    kAmpFault | kAmpCommsLost | kAmpDisabledUnexpectedly | kAmpMismatch;
// The biometrics box's problems. They spoil a recording, never the motor's
// safety: none of them may stop torque.
inline constexpr std::uint32_t kBiometricsMask =
    kBiometricsLost | kBiometricsStale | kBiometricsException | kBiometricsMismatch;
static_assert((kAmpTripMask & kBiometricsMask) == 0, "a biometrics problem must never cut torque");

// "amp-fault|amp-comms-lost" style, for logs ("ok" if no bit is set).
std::string describe(std::uint32_t word);

}  // namespace knoblab::modbus::status
