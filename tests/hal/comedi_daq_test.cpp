// ComediDaq against a fake DAS1602: validation at open, scaling and wrap in
// the loop, the safe 0 V on open, disable and close.
#include "knoblab/hal/comedi_daq.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "fake_comedi.hpp"
#include "test_util.hpp"

namespace knoblab::hal {
namespace {

using test::error_of;
using test::FakeComedi;
using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr unsigned kAi = 0, kAo = 1, kCounter = 3;
const std::string kBoard = "/dev/comedi0";

ComediDaqConfig thesis_config() {
  ComediDaqConfig c;
  c.device = kBoard;
  c.torque = {.subdevice = kAi, .channel = 0, .range_V = VoltRange{-1.25, 1.25}, .aref = Aref::Diff};
  c.accel = {.subdevice = kAi, .channel = 1, .range_V = VoltRange{-5.0, 5.0}};
  c.motor = {.subdevice = kAo, .channel = 0, .range_V = VoltRange{-10.0, 10.0}};
  c.encoder = {.subdevice = kCounter, .channel = 0};
  return c;
}

class ComediDaqTest : public ::testing::Test {
 protected:
  ComediDaqTest() {
    api.boards[kBoard] = test::das1602();
    api.boards["/dev/comedi1"] = test::encoder_card();
  }
  std::string open_error(const ComediDaqConfig& c) {
    return error_of<std::runtime_error>([&] { ComediDaq daq(c, api); });
  }
  std::uint32_t motor_code() { return api.get(kBoard, kAo, 0); }

  FakeComedi api;
};

TEST_F(ComediDaqTest, WritesZeroVoltsBeforeTouchingAnythingElse) {
  api.set(kBoard, kAo, 0, 4095);  // a stale full-scale command from a crashed run
  ComediDaq daq(thesis_config(), api);
  ASSERT_GE(api.log.size(), 2u);
  EXPECT_EQ(api.log[0], "open " + kBoard);
  EXPECT_EQ(api.log[1], "write 1/0=2048");  // ±10 V, 12 bit: 0 V is code 2048
}

TEST_F(ComediDaqTest, ScalesTheThesisTorqueChannel) {
  ComediDaq daq(thesis_config(), api);
  capture::DaqInputs in;
  api.set(kBoard, kAi, 0, 65535);
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_NEAR(in.torque_V, 1.25, 1e-12);
  api.set(kBoard, kAi, 0, 0);
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_DOUBLE_EQ(in.torque_V, -1.25);
  api.set(kBoard, kAi, 0, 49152);  // 3/4 of the way up
  api.set(kBoard, kAi, 1, 16384);
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_NEAR(in.torque_V, -1.25 + 2.5 * 49152.0 / 65535.0, 1e-12);
  EXPECT_NEAR(in.accel_V, -5.0 + 10.0 * 16384.0 / 65535.0, 1e-12);
}

TEST_F(ComediDaqTest, RangeByIndexAndGainOffsetApply) {
  ComediDaqConfig c = thesis_config();
  c.accel.range_V.reset();
  c.accel.range = 4;  // 0–10 V
  c.accel.gain = 0.5;
  c.accel.offset_V = 1.0;
  ComediDaq daq(c, api);
  api.set(kBoard, kAi, 1, 65535);
  capture::DaqInputs in;
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_NEAR(in.accel_V, 0.5 * 10.0 + 1.0, 1e-12);
}

TEST_F(ComediDaqTest, EncoderCountsRunOnAcrossThe24BitWrap) {
  api.set(kBoard, kCounter, 0, 0xFFFFFE);  // −2 at open
  ComediDaq daq(thesis_config(), api);
  capture::DaqInputs in;
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_EQ(in.encoder_counts, -2);
  api.set(kBoard, kCounter, 0, 0x000005);
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_EQ(in.encoder_counts, 5);
  std::uint32_t raw = 5;
  for (int i = 0; i < 300; ++i) {  // 300 × 64 000 counts = 30 revolutions, > 2^24
    raw = (raw + 64000) & 0xFFFFFF;
    api.set(kBoard, kCounter, 0, raw);
    EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  }
  EXPECT_EQ(in.encoder_counts, 5 + 300 * 64000);
}

TEST_F(ComediDaqTest, EncoderOnASeparateCardWithSignAndReset) {
  ComediDaqConfig c = thesis_config();
  c.encoder = {.device = "/dev/comedi1", .subdevice = std::nullopt, .channel = 2, .reset_on_open = true, .sign = -1};
  api.set("/dev/comedi1", 0, 2, 12345);
  ComediDaq daq(c, api);
  EXPECT_EQ(api.open_devices, 2);
  EXPECT_THAT(api.log, ::testing::Contains("reset 0/2"));
  capture::DaqInputs in;
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_EQ(in.encoder_counts, 0);
  api.set("/dev/comedi1", 0, 2, 0xFFFFFFFFu - 9);  // ten counts backwards through zero
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  EXPECT_EQ(in.encoder_counts, 10);  // sign −1
}

TEST_F(ComediDaqTest, CommandIsScaledClampedAndZeroWhenDisabled) {
  ComediDaq daq(thesis_config(), api);
  EXPECT_EQ(daq.write({.motor_command_V = 5.0, .amp_enable = true}), capture::IoStatus::ok);
  EXPECT_EQ(motor_code(), 3071u);  // round((5 + 10) · 4095/20) = round(3071.25)
  EXPECT_EQ(daq.write({.motor_command_V = 20.0, .amp_enable = true}), capture::IoStatus::ok);
  EXPECT_EQ(motor_code(), 4095u);
  EXPECT_EQ(daq.write({.motor_command_V = -20.0, .amp_enable = true}), capture::IoStatus::ok);
  EXPECT_EQ(motor_code(), 0u);
  EXPECT_EQ(daq.stats().clamped_writes, 2u);
  EXPECT_EQ(daq.write({.motor_command_V = 5.0, .amp_enable = false}), capture::IoStatus::ok);
  EXPECT_EQ(motor_code(), 2048u);
  EXPECT_EQ(daq.write({.motor_command_V = std::numeric_limits<double>::quiet_NaN(), .amp_enable = true}), capture::IoStatus::ok);
  EXPECT_EQ(motor_code(), 2048u);
  EXPECT_EQ(daq.stats().clamped_writes, 2u);
}

TEST_F(ComediDaqTest, MotorGainReversesTheCommand) {
  ComediDaqConfig c = thesis_config();
  c.motor.gain = -1.0;
  ComediDaq daq(c, api);
  EXPECT_EQ(daq.write({.motor_command_V = 10.0, .amp_enable = true}), capture::IoStatus::ok);
  EXPECT_EQ(motor_code(), 0u);
}

TEST_F(ComediDaqTest, ClosingWritesZeroVoltsAndClosesTheDevice) {
  {
    ComediDaq daq(thesis_config(), api);
    EXPECT_EQ(daq.write({.motor_command_V = 7.5, .amp_enable = true}), capture::IoStatus::ok);
    EXPECT_NE(motor_code(), 2048u);
  }
  EXPECT_EQ(motor_code(), 2048u);
  EXPECT_EQ(api.open_devices, 0);
  EXPECT_EQ(api.log.back(), "close " + kBoard);
}

TEST_F(ComediDaqTest, FailedReadsAndWritesReportAnErrorKeepTheLastValueAndAreCounted) {
  ComediDaq daq(thesis_config(), api);
  api.set(kBoard, kAi, 0, 65535);
  api.set(kBoard, kCounter, 0, 100);
  capture::DaqInputs in;
  EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
  api.fail_reads = true;
  api.set(kBoard, kAi, 0, 0);
  EXPECT_EQ(daq.read(in), capture::IoStatus::error);
  EXPECT_NEAR(in.torque_V, 1.25, 1e-12);
  EXPECT_EQ(in.encoder_counts, 100);
  EXPECT_EQ(daq.stats().read_errors, 3u);  // torque, accel, encoder
  EXPECT_EQ(daq.write({.motor_command_V = 1.0, .amp_enable = true}), capture::IoStatus::ok);
  api.fail_writes = true;
  EXPECT_EQ(daq.write({.motor_command_V = 1.0, .amp_enable = true}), capture::IoStatus::error);
  EXPECT_EQ(daq.stats().write_errors, 1u);
}

TEST_F(ComediDaqTest, FindsSubdevicesByTypeWhenNotGiven) {
  ComediDaqConfig c = thesis_config();
  c.torque.subdevice.reset();
  c.motor.subdevice.reset();
  c.encoder.subdevice.reset();
  ComediDaq daq(c, api);
  EXPECT_THAT(daq.description(), AllOf(HasSubstr("torque: /dev/comedi0 subdevice 0 channel 0, range 3 [-1.25, 1.25] V, aref diff, 16-bit"),
                                       HasSubstr("motor: /dev/comedi0 subdevice 1 channel 0, range 1 [-10, 10] V"),
                                       HasSubstr("encoder: /dev/comedi0 subdevice 3 channel 0, 24-bit")));
}

// --- every way opening can fail names the device, subdevice and channel ---

TEST_F(ComediDaqTest, MissingDeviceNamesThePath) {
  ComediDaqConfig c = thesis_config();
  c.device = "/dev/comedi7";
  EXPECT_EQ(open_error(c), "cannot open Comedi device /dev/comedi7: No such file or directory");
  c = thesis_config();
  c.encoder.device = "/dev/comedi5";
  EXPECT_EQ(open_error(c), "cannot open Comedi device /dev/comedi5: No such file or directory");
  EXPECT_EQ(api.open_devices, 0);  // the board opened first was closed again
}

TEST_F(ComediDaqTest, WrongSubdeviceTypeIsNamed) {
  ComediDaqConfig c = thesis_config();
  c.torque.subdevice = kAo;
  EXPECT_EQ(open_error(c), "torque: /dev/comedi0 subdevice 1 is analog-output, not analog-input");
  c = thesis_config();
  c.encoder.subdevice = 2;
  EXPECT_EQ(open_error(c), "encoder: /dev/comedi0 subdevice 2 is digital-I/O, not counter");
  c = thesis_config();
  c.motor.subdevice = 9;
  EXPECT_EQ(open_error(c), "motor: /dev/comedi0 has 4 subdevices; subdevice 9 does not exist");
}

TEST_F(ComediDaqTest, MissingSubdeviceTypeIsNamed) {
  api.sub(kBoard, kCounter).type = 7;  // a board without counters
  ComediDaqConfig c = thesis_config();
  c.encoder.subdevice.reset();
  EXPECT_EQ(open_error(c), "encoder: /dev/comedi0 has no counter subdevice");
}

TEST_F(ComediDaqTest, ChannelOutOfRangeIsNamed) {
  ComediDaqConfig c = thesis_config();
  c.accel.channel = 8;
  EXPECT_EQ(open_error(c), "accel: /dev/comedi0 subdevice 0 has 8 channels; channel 8 does not exist");
}

TEST_F(ComediDaqTest, UnavailableRangeListsWhatExists) {
  ComediDaqConfig c = thesis_config();
  c.torque.range_V = VoltRange{-1.0, 1.0};
  EXPECT_THAT(open_error(c), AllOf(HasSubstr("torque: /dev/comedi0 subdevice 0 channel 0 has no range [-1, 1] V"),
                                   HasSubstr("available: 0 [-10, 10] V, 1 [-5, 5] V, 2 [-2.5, 2.5] V, 3 [-1.25, 1.25] V")));
  c = thesis_config();
  c.motor.range_V.reset();
  c.motor.range = 4;
  EXPECT_THAT(open_error(c), HasSubstr("motor: /dev/comedi0 subdevice 1 channel 0 has no range 4 (available: 0 [-5, 5] V"));
}

TEST_F(ComediDaqTest, NonVoltOrExternalRangesAreRefused) {
  api.sub(kBoard, kAi).ranges[3].unit = 1;  // mA
  EXPECT_THAT(open_error(thesis_config()), HasSubstr("torque: /dev/comedi0 subdevice 0 channel 0 range 3 is not in volts"));
  api.sub(kBoard, kAi).ranges[3].unit = comedi::kUnitVolt | comedi::kRangeExternal;
  EXPECT_THAT(open_error(thesis_config()), HasSubstr("range 3 is relative to an external reference"));
}

TEST_F(ComediDaqTest, UnsupportedReferenceIsNamed) {
  api.sub(kBoard, kAi).flags = comedi::kFlagGround;
  EXPECT_EQ(open_error(thesis_config()), "torque: /dev/comedi0 subdevice 0 does not support aref diff (supports: ground)");
}

TEST_F(ComediDaqTest, FailingCounterResetAndReadsAreNamed) {
  api.boards[kBoard].reset_supported = false;
  ComediDaqConfig c = thesis_config();
  c.encoder.reset_on_open = true;
  EXPECT_EQ(open_error(c), "encoder: /dev/comedi0 subdevice 3 channel 0: reset (INSN_CONFIG_RESET) failed: Invalid argument");
  api.fail_writes = true;
  EXPECT_EQ(open_error(thesis_config()), "motor: /dev/comedi0 subdevice 1 channel 0: writing 0 V failed: Input/output error");
  api.fail_writes = false;
  api.fail_reads = true;
  EXPECT_EQ(open_error(thesis_config()), "torque: /dev/comedi0 subdevice 0 channel 0: reading failed: Input/output error");
}

// The real comedilib on a machine without a board fails cleanly, naming the path.
TEST(SystemComediApi, FailsCleanlyWithoutABoard) {
  ComediDaqConfig c = thesis_config();
  c.device = "/nonexistent/comedi0";
  EXPECT_EQ(error_of<std::runtime_error>([&] { ComediDaq daq(c); }),
            "cannot open Comedi device /nonexistent/comedi0: No such file or directory");
  if (std::filesystem::exists("/dev/comedi0")) GTEST_SKIP() << "this machine has /dev/comedi0";
  c.device = "/dev/comedi0";
  EXPECT_THAT(error_of<std::runtime_error>([&] { ComediDaq daq(c); }),
              HasSubstr("/dev/comedi0: No such file or directory"));
}

}  // namespace
}  // namespace knoblab::hal
