#include "knoblab/modbus/codec.hpp"

#include <cmath>
#include <limits>

namespace knoblab::modbus {
namespace {

double from_i16(std::uint16_t raw, double per_lsb) {
  return static_cast<double>(static_cast<std::int16_t>(raw)) * per_lsb;
}

double from_u16(std::uint16_t raw, double per_lsb) { return static_cast<double>(raw) * per_lsb; }

std::uint16_t as_register(std::int16_t v) { return static_cast<std::uint16_t>(v); }

}  // namespace

std::int16_t to_i16(double value, double per_lsb) {
  const double lsb = std::round(value / per_lsb);
  if (std::isnan(lsb)) return 0;
  if (lsb <= std::numeric_limits<std::int16_t>::min()) return std::numeric_limits<std::int16_t>::min();
  if (lsb >= std::numeric_limits<std::int16_t>::max()) return std::numeric_limits<std::int16_t>::max();
  return static_cast<std::int16_t>(lsb);
}

std::uint16_t to_u16(double value, double per_lsb) {
  const double lsb = std::round(value / per_lsb);
  if (!(lsb > 0.0)) return 0;  // also NaN
  if (lsb >= std::numeric_limits<std::uint16_t>::max()) return std::numeric_limits<std::uint16_t>::max();
  return static_cast<std::uint16_t>(lsb);
}

bool identity_matches(std::span<const std::uint16_t> block, DeviceType expected) {
  return block.size() > ident::kDeviceType && block[ident::kMapVersion] == kMapVersion &&
         block[ident::kDeviceType] == static_cast<std::uint16_t>(expected);
}

std::optional<AmplifierStatus> decode_amplifier(std::span<const std::uint16_t> block) {
  if (block.size() < amp::kInputCount || !identity_matches(block, DeviceType::amplifier))
    return std::nullopt;
  AmplifierStatus s;
  s.status = block[amp::kStatus];
  s.faults = block[amp::kFaults];
  s.bus_voltage = from_u16(block[amp::kBusVoltage], amp::kVoltsPerLsb);
  s.temperature = from_i16(block[amp::kTemperature], amp::kCelsiusPerLsb);
  s.current = from_i16(block[amp::kCurrent], amp::kAmpsPerLsb);
  s.current_limit = from_u16(block[amp::kCurrentLimit], amp::kAmpsPerLsb);
  s.heartbeat = block[amp::kHeartbeat];
  return s;
}

void encode_amplifier(const AmplifierStatus& s, std::span<std::uint16_t> block) {
  if (block.size() < amp::kInputCount) return;
  block[ident::kMapVersion] = kMapVersion;
  block[ident::kDeviceType] = static_cast<std::uint16_t>(DeviceType::amplifier);
  block[amp::kStatus] = s.status;
  block[amp::kFaults] = s.faults;
  block[amp::kBusVoltage] = to_u16(s.bus_voltage, amp::kVoltsPerLsb);
  block[amp::kTemperature] = as_register(to_i16(s.temperature, amp::kCelsiusPerLsb));
  block[amp::kCurrent] = as_register(to_i16(s.current, amp::kAmpsPerLsb));
  block[amp::kCurrentLimit] = to_u16(s.current_limit, amp::kAmpsPerLsb);
  block[amp::kHeartbeat] = s.heartbeat;
}

std::optional<BiometricsSnapshot> decode_biometrics(std::span<const std::uint16_t> block) {
  if (block.size() < bio::kInputCount || !identity_matches(block, DeviceType::biometrics) ||
      block[bio::kRingSizeReg] != bio::kRingSize || block[bio::kRecordSizeReg] != bio::kRecordSize)
    return std::nullopt;
  BiometricsSnapshot s;
  s.status = block[bio::kStatus];
  s.rate_hz = block[bio::kSampleRate];
  s.latest_counter = join_u32(block[bio::kLatestCounter], block[bio::kLatestCounter + 1]);
  for (std::size_t i = 0; i < bio::kRingSize; ++i) {
    const auto r = block.subspan(bio::kRingBase + i * bio::kRecordSize, bio::kRecordSize);
    BiometricSample& out = s.ring[i];
    out.counter = join_u32(r[bio::record::kCounter], r[bio::record::kCounter + 1]);
    out.box_time_ms = join_u32(r[bio::record::kBoxTime], r[bio::record::kBoxTime + 1]);
    out.emg_corrugator = from_i16(r[bio::record::kEmgCorrugator], bio::kVoltsPerLsb);
    out.emg_depressor = from_i16(r[bio::record::kEmgDepressor], bio::kVoltsPerLsb);
    out.skin_conductance = from_u16(r[bio::record::kSkinConductance], bio::kSiemensPerLsb);
    out.flags = r[bio::record::kFlags];
  }
  return s;
}

void encode_biometrics_header(const BiometricsSnapshot& s, std::span<std::uint16_t> block) {
  if (block.size() < bio::kRingBase) return;
  block[ident::kMapVersion] = kMapVersion;
  block[ident::kDeviceType] = static_cast<std::uint16_t>(DeviceType::biometrics);
  block[bio::kStatus] = s.status;
  block[bio::kSampleRate] = s.rate_hz;
  block[bio::kLatestCounter] = high_word(s.latest_counter);
  block[bio::kLatestCounter + 1] = low_word(s.latest_counter);
  block[bio::kRingSizeReg] = bio::kRingSize;
  block[bio::kRecordSizeReg] = bio::kRecordSize;
}

void encode_biometric_record(const BiometricSample& s, std::span<std::uint16_t> block) {
  const std::size_t at = bio::kRingBase + (s.counter % bio::kRingSize) * bio::kRecordSize;
  if (block.size() < at + bio::kRecordSize) return;
  auto r = block.subspan(at, bio::kRecordSize);
  r[bio::record::kCounter] = high_word(s.counter);
  r[bio::record::kCounter + 1] = low_word(s.counter);
  r[bio::record::kBoxTime] = high_word(s.box_time_ms);
  r[bio::record::kBoxTime + 1] = low_word(s.box_time_ms);
  r[bio::record::kEmgCorrugator] = as_register(to_i16(s.emg_corrugator, bio::kVoltsPerLsb));
  r[bio::record::kEmgDepressor] = as_register(to_i16(s.emg_depressor, bio::kVoltsPerLsb));
  r[bio::record::kSkinConductance] = to_u16(s.skin_conductance, bio::kSiemensPerLsb);
  r[bio::record::kFlags] = s.flags;
}

}  // namespace knoblab::modbus
