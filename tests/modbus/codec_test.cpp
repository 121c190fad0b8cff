// Register layouts and unit conversions: what goes on the wire is what
// docs/modbus.md says.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "knoblab/modbus/codec.hpp"
#include "knoblab/modbus/register_map.hpp"

namespace knoblab::modbus {
namespace {

TEST(RegisterMap, BlocksFitOneRead) {
  EXPECT_LE(amp::kInputCount, 125);  // MODBUS_MAX_READ_REGISTERS
  EXPECT_LE(bio::kInputCount, 125);
  EXPECT_EQ(bio::kInputCount, 72);
  EXPECT_EQ(bio::kRingBase + bio::kRingSize * bio::kRecordSize, bio::kInputCount);
}

TEST(RegisterMap, ThirtyTwoBitValuesAreHighWordFirst) {
  EXPECT_EQ(high_word(0x12345678u), 0x1234);
  EXPECT_EQ(low_word(0x12345678u), 0x5678);
  EXPECT_EQ(join_u32(0x1234, 0x5678), 0x12345678u);
}

TEST(Codec, AmplifierRoundTripsInSiUnits) {
  AmplifierStatus in;
  in.status = amp::status::kEnabled | amp::status::kEnableRequested;
  in.faults = amp::fault::kOverTemperature;
  in.bus_voltage = 48.07;
  in.temperature = -3.4;
  in.current = -12.345;
  in.current_limit = 20.0;
  in.heartbeat = 65535;
  std::array<std::uint16_t, amp::kInputCount> regs{};
  encode_amplifier(in, regs);
  EXPECT_EQ(regs[amp::kBusVoltage], 4807);                         // 10 mV
  EXPECT_EQ(static_cast<std::int16_t>(regs[amp::kTemperature]), -34);  // 0.1 °C
  EXPECT_EQ(static_cast<std::int16_t>(regs[amp::kCurrent]), -12345);   // mA
  const auto out = decode_amplifier(regs);
  ASSERT_TRUE(out);
  EXPECT_TRUE(out->enabled());
  EXPECT_EQ(out->faults, amp::fault::kOverTemperature);
  EXPECT_NEAR(out->bus_voltage, 48.07, 1e-9);
  EXPECT_NEAR(out->temperature, -3.4, 1e-9);
  EXPECT_NEAR(out->current, -12.345, 1e-9);
  EXPECT_NEAR(out->current_limit, 20.0, 1e-9);
  EXPECT_EQ(out->heartbeat, 65535);
}

TEST(Codec, BiometricRecordRoundTripsAndLandsInItsRingSlot) {
  std::array<std::uint16_t, bio::kInputCount> regs{};
  BiometricsSnapshot header;
  header.rate_hz = 32;
  header.latest_counter = 0x00010009;
  encode_biometrics_header(header, regs);
  BiometricSample s;
  s.counter = 0x00010009;
  s.box_time_ms = 0xDEADBEEF;
  s.emg_corrugator = -123.4e-6;
  s.emg_depressor = 3276.7e-6;   // the int16 ceiling at 0.1 µV
  s.skin_conductance = 5.43e-6;  // 543 × 0.01 µS
  encode_biometric_record(s, regs);
  const std::size_t at = bio::kRingBase + (s.counter % bio::kRingSize) * bio::kRecordSize;
  EXPECT_EQ(regs[at + bio::record::kCounter], 0x0001);
  EXPECT_EQ(regs[at + bio::record::kCounter + 1], 0x0009);
  EXPECT_EQ(regs[at + bio::record::kSkinConductance], 543);

  const auto out = decode_biometrics(regs);
  ASSERT_TRUE(out);
  EXPECT_EQ(out->latest_counter, 0x00010009u);
  const BiometricSample& r = out->ring[s.counter % bio::kRingSize];
  EXPECT_EQ(r.counter, s.counter);
  EXPECT_EQ(r.box_time_ms, 0xDEADBEEFu);
  EXPECT_NEAR(r.emg_corrugator, -123.4e-6, 1e-12);
  EXPECT_NEAR(r.emg_depressor, 3276.7e-6, 1e-12);
  EXPECT_NEAR(r.skin_conductance, 5.43e-6, 1e-12);
}

TEST(Codec, OutOfRangeValuesSaturate) {
  EXPECT_EQ(to_i16(1.0, 1e-7), 32767);
  EXPECT_EQ(to_i16(-1.0, 1e-7), -32768);
  EXPECT_EQ(to_u16(-5.0, 0.01), 0);
  EXPECT_EQ(to_u16(1e9, 0.01), 65535);
}

TEST(Codec, WrongIdentityIsRejected) {
  std::array<std::uint16_t, bio::kInputCount> regs{};
  encode_biometrics_header({}, regs);
  EXPECT_TRUE(decode_biometrics(regs));
  EXPECT_FALSE(decode_amplifier(regs));  // a biometrics box at the amp's unit id
  regs[ident::kMapVersion] = kMapVersion + 1;
  EXPECT_FALSE(decode_biometrics(regs));
  EXPECT_FALSE(decode_biometrics(std::span(regs).first(10)));
}

}  // namespace
}  // namespace knoblab::modbus
