// Register blocks <-> SI values. The only place register units appear;
// everything above this layer works in V, A, S, °C and seconds.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>

#include "knoblab/modbus/register_map.hpp"

namespace knoblab::modbus {

struct AmplifierStatus {
  std::uint16_t status = 0;  // amp::status bits
  std::uint16_t faults = 0;  // amp::fault bits
  double bus_voltage = 0.0;  // V
  double temperature = 0.0;  // °C
  double current = 0.0;      // A, signed
  double current_limit = 0.0;// A, the limit in force
  std::uint16_t heartbeat = 0;

  bool enabled() const { return (status & amp::status::kEnabled) != 0; }
};

struct BiometricSample {
  std::uint32_t counter = 0;      // the box's 32 Hz sample counter (1, 2, …)
  std::uint32_t box_time_ms = 0;  // the box's own clock
  double emg_corrugator = 0.0;    // V, signed
  double emg_depressor = 0.0;     // V, signed
  double skin_conductance = 0.0;  // S
  std::uint16_t flags = 0;        // bio::status bits at this sample
  // When the poller received it (steady clock).
  std::chrono::steady_clock::time_point received{};
  // When the box took it, on the same clock (box_time_ms mapped by BoxClock):
  // for aligning with the loop. Unlike `received`, a late poll does not move it.
  std::chrono::steady_clock::time_point taken{};
};

// One read of the biometrics block: header plus the ring, as the box holds it.
struct BiometricsSnapshot {
  std::uint16_t status = 0;
  std::uint16_t rate_hz = 0;
  std::uint32_t latest_counter = 0;  // 0 = no sample yet
  std::array<BiometricSample, bio::kRingSize> ring{};  // ring[c % kRingSize]
};

// Identity check shared by every unit; false if the block is too short or
// the map version / device type differ.
bool identity_matches(std::span<const std::uint16_t> block, DeviceType expected);

// Decoders take a block read from register 0; nullopt if it is too short or
// its identity or layout is not the expected one.
std::optional<AmplifierStatus> decode_amplifier(std::span<const std::uint16_t> block);
std::optional<BiometricsSnapshot> decode_biometrics(std::span<const std::uint16_t> block);

// Encoders, used by the simulator (and tests) to fill register images.
void encode_amplifier(const AmplifierStatus& s, std::span<std::uint16_t> block);
void encode_biometrics_header(const BiometricsSnapshot& s, std::span<std::uint16_t> block);
void encode_biometric_record(const BiometricSample& s, std::span<std::uint16_t> block);

// Saturating conversions from SI to register units.
std::int16_t to_i16(double value, double per_lsb);
std::uint16_t to_u16(double value, double per_lsb);

}  // namespace knoblab::modbus
