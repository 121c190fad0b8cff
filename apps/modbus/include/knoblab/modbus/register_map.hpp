// Register maps of the two Modbus devices hapticd talks to, and of the
// simulator's control block. docs/modbus.md is the user-facing copy of this
// file; change both together and bump kMapVersion on any incompatible change.
//
// Conventions (all units):
// * Addresses are 0-based protocol addresses (what goes on the wire).
// * Input registers (FC 04) hold measurements, holding registers (FC 03/06/16)
//   hold commands. Coils and discrete inputs are not used.
// * Every unit starts its input registers with the same identity block:
//   IR 0 = map version, IR 1 = device type. The poller checks both on every
//   read, so a swapped unit id or an old firmware is caught, not misread.
// * 32-bit values take two registers, HIGH word first (big-endian words,
//   "ABCD"), the order libmodbus' MODBUS_GET_INT32_FROM_INT16 expects.
// * Signed 16-bit values are two's complement.
#pragma once

#include <cstdint>

namespace knoblab::modbus {

inline constexpr std::uint16_t kMapVersion = 1;

enum class DeviceType : std::uint16_t {
  amplifier = 1,
  biometrics = 2,
  sim_control = 3,
};

inline constexpr int kDefaultAmplifierUnit = 1;
inline constexpr int kDefaultBiometricsUnit = 2;
inline constexpr int kDefaultSimControlUnit = 247;  // highest legal unit id

// Identity block, identical on every unit (input registers).
namespace ident {
inline constexpr std::uint16_t kMapVersion = 0;  // = modbus::kMapVersion
inline constexpr std::uint16_t kDeviceType = 1;  // DeviceType
}  // namespace ident

// ---------------------------------------------------------------------------
// Servo amplifier (Copley 2122 class: 10 A continuous, 20 A peak; thesis §1.3)
// ---------------------------------------------------------------------------
namespace amp {

// Input registers (FC 04), read as one block of kInputCount.
inline constexpr std::uint16_t kStatus = 2;         // StatusBit
inline constexpr std::uint16_t kFaults = 3;         // FaultBit, latched
inline constexpr std::uint16_t kBusVoltage = 4;     // uint16, 10 mV/LSB
inline constexpr std::uint16_t kTemperature = 5;    // int16, 0.1 °C/LSB
inline constexpr std::uint16_t kCurrent = 6;        // int16, 1 mA/LSB, signed
inline constexpr std::uint16_t kCurrentLimit = 7;   // uint16, mA in force
inline constexpr std::uint16_t kHeartbeat = 8;      // uint16, +1 per ms, wraps
inline constexpr std::uint16_t kInputCount = 9;

// Holding registers (FC 03/06/16).
inline constexpr std::uint16_t kEnableCommand = 0;        // 1 = enable, 0 = disable
inline constexpr std::uint16_t kCurrentLimitCommand = 1;  // uint16 mA, clamped to peak
inline constexpr std::uint16_t kFaultReset = 2;           // write 1: clear latched faults
inline constexpr std::uint16_t kHoldingCount = 3;

namespace status {
inline constexpr std::uint16_t kEnabled = 1u << 0;         // output stage on
inline constexpr std::uint16_t kFaulted = 1u << 1;         // fault word != 0
inline constexpr std::uint16_t kCurrentLimiting = 1u << 2; // |I| clamped at the limit
inline constexpr std::uint16_t kEnableRequested = 1u << 3; // mirror of kEnableCommand
}  // namespace status

// Fault word. A fault latches, disables the output stage and stays set
// until kFaultReset is written while its cause has gone.
namespace fault {
inline constexpr std::uint16_t kOverCurrent = 1u << 0;
inline constexpr std::uint16_t kOverTemperature = 1u << 1;
inline constexpr std::uint16_t kUnderVoltage = 1u << 2;
inline constexpr std::uint16_t kOverVoltage = 1u << 3;
inline constexpr std::uint16_t kMotorShort = 1u << 4;    // output short circuit
inline constexpr std::uint16_t kFeedback = 1u << 5;      // encoder/Hall feedback
inline constexpr std::uint16_t kInternal = 1u << 6;      // drive hardware fault
inline constexpr std::uint16_t kAll = 0x7F;
}  // namespace fault

inline constexpr double kContinuousCurrent = 10.0;  // A
inline constexpr double kPeakCurrent = 20.0;        // A: the command clamp

// Register units, converted at the edge (codec.cpp).
inline constexpr double kVoltsPerLsb = 0.01;
inline constexpr double kCelsiusPerLsb = 0.1;
inline constexpr double kAmpsPerLsb = 0.001;

}  // namespace amp

// ---------------------------------------------------------------------------
// Biometrics box (thesis §4.4.1.2: EMG corrugator + depressor supercilii and
// skin conductance, all at 32 Hz)
// ---------------------------------------------------------------------------
// The box keeps its last kRingSize samples in a ring so that one FC 04 read
// of kInputCount registers returns them all, consistently. A poller that
// misses a poll (a scheduling hiccup, a quick reconnect) backfills from the
// ring instead of losing samples; the counter de-duplicates.
namespace bio {

// Input registers (FC 04), read as one block of kInputCount.
inline constexpr std::uint16_t kStatus = 2;         // StatusBit
inline constexpr std::uint16_t kSampleRate = 3;     // Hz (32)
inline constexpr std::uint16_t kLatestCounter = 4;  // uint32, 2 registers; 0 = none yet
inline constexpr std::uint16_t kRingSizeReg = 6;    // = kRingSize
inline constexpr std::uint16_t kRecordSizeReg = 7;  // = kRecordSize
inline constexpr std::uint16_t kRingBase = 8;

inline constexpr std::uint16_t kRingSize = 8;    // samples (250 ms at 32 Hz)
inline constexpr std::uint16_t kRecordSize = 8;  // registers per sample
// Sample with counter c sits at kRingBase + (c % kRingSize) * kRecordSize.
namespace record {
inline constexpr std::uint16_t kCounter = 0;          // uint32, 2 registers, starts at 1
inline constexpr std::uint16_t kBoxTime = 2;          // uint32 ms, box's own clock, 2 registers
inline constexpr std::uint16_t kEmgCorrugator = 4;    // int16, 0.1 µV/LSB
inline constexpr std::uint16_t kEmgDepressor = 5;     // int16, 0.1 µV/LSB
inline constexpr std::uint16_t kSkinConductance = 6;  // uint16, 0.01 µS/LSB
inline constexpr std::uint16_t kFlags = 7;            // StatusBit at that sample
}  // namespace record

inline constexpr std::uint16_t kInputCount = kRingBase + kRingSize * kRecordSize;  // 72

namespace status {
inline constexpr std::uint16_t kSampling = 1u << 0;
inline constexpr std::uint16_t kCorrugatorLeadOff = 1u << 1;
inline constexpr std::uint16_t kDepressorLeadOff = 1u << 2;
inline constexpr std::uint16_t kSkinConductanceLeadOff = 1u << 3;
}  // namespace status

inline constexpr std::uint16_t kRateHz = 32;
inline constexpr double kVoltsPerLsb = 1e-7;     // EMG: 0.1 µV
inline constexpr double kSiemensPerLsb = 1e-8;   // SC: 0.01 µS

}  // namespace bio

// ---------------------------------------------------------------------------
// Simulator control (knoblab-modbus-sim only; unit kDefaultSimControlUnit).
// Lets tests inject faults into a running simulator. Writes act at once.
// ---------------------------------------------------------------------------
namespace simctl {

// Holding registers (FC 03/06/16).
inline constexpr std::uint16_t kAmpException = 0;   // 0 = off, else exception code for every amp request
inline constexpr std::uint16_t kBioException = 1;   // same for the biometrics unit
inline constexpr std::uint16_t kFreeze = 2;         // FreezeBit: values and counters stop
inline constexpr std::uint16_t kAmpFaultInject = 3; // amp::fault bits whose cause is present
inline constexpr std::uint16_t kDropConnections = 4;// write N: drop every client, refuse new ones N ms
inline constexpr std::uint16_t kMute = 5;           // MuteBit: requests get no reply (a hung device)
inline constexpr std::uint16_t kStimulus = 6;       // write 1: present a stimulus now
inline constexpr std::uint16_t kAmpReplyDelay = 7;  // ms each amp reply is held back (a slow device); 0 = off
inline constexpr std::uint16_t kBioReplyDelay = 8;  // same for the biometrics unit
inline constexpr std::uint16_t kAmpMapVersion = 9;  // the map version the amp reports (other firmware); 0 = kMapVersion
inline constexpr std::uint16_t kBioMapVersion = 10; // same for the biometrics unit
inline constexpr std::uint16_t kHoldingCount = 11;

// Input registers (FC 04) after the identity block.
inline constexpr std::uint16_t kRequestsServed = 2;  // uint32, 2 registers
inline constexpr std::uint16_t kBadFrames = 4;       // uint16, saturating
inline constexpr std::uint16_t kClients = 5;         // connected clients now
inline constexpr std::uint16_t kInputCount = 6;

inline constexpr std::uint16_t kFreezeBiometrics = 1u << 0;
inline constexpr std::uint16_t kFreezeAmplifier = 1u << 1;
inline constexpr std::uint16_t kMuteAmplifier = 1u << 0;
inline constexpr std::uint16_t kMuteBiometrics = 1u << 1;

}  // namespace simctl

// 32-bit values in two registers, high word first.
constexpr std::uint32_t join_u32(std::uint16_t high, std::uint16_t low) {
  return (std::uint32_t{high} << 16) | low;
}
constexpr std::uint16_t high_word(std::uint32_t v) { return static_cast<std::uint16_t>(v >> 16); }
constexpr std::uint16_t low_word(std::uint32_t v) { return static_cast<std::uint16_t>(v & 0xFFFFu); }

}  // namespace knoblab::modbus
