// knoblab-modbus-sim --fault specs.
#include <gtest/gtest.h>

#include "knoblab/modbus/fault_spec.hpp"
#include "knoblab/modbus/register_map.hpp"

namespace knoblab::modbus {
namespace {

TEST(FaultSpec, Disconnect) {
  auto f = parse_fault("disconnect-after=1.5", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->kind, FaultAction::Kind::disconnect);
  EXPECT_DOUBLE_EQ(f->at_seconds, 1.5);
  EXPECT_EQ(f->refuse_for.count(), 1000);
  f = parse_fault("disconnect-after=2:250", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->refuse_for.count(), 250);
}

TEST(FaultSpec, Exception) {
  auto f = parse_fault("exception=gateway-target:bio@0.5", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->kind, FaultAction::Kind::exception);
  EXPECT_EQ(f->exception_code, 11);
  EXPECT_FALSE(f->to_amplifier);
  EXPECT_TRUE(f->to_biometrics);
  EXPECT_DOUBLE_EQ(f->at_seconds, 0.5);
  f = parse_fault("exception=4", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->exception_code, 4);
  EXPECT_TRUE(f->to_amplifier && f->to_biometrics);
}

TEST(FaultSpec, StaleAndAmpFault) {
  auto f = parse_fault("stale-after=3", nullptr);
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->to_biometrics);
  EXPECT_FALSE(f->to_amplifier);
  f = parse_fault("amp-fault-after=0.2:over-current+motor-short", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->fault_bits, amp::fault::kOverCurrent | amp::fault::kMotorShort);
  f = parse_fault("amp-fault-after=1:0x02", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->fault_bits, amp::fault::kOverTemperature);
}

TEST(FaultSpec, SlowAndHang) {
  auto f = parse_fault("slow=300:bio@1.5", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->kind, FaultAction::Kind::slow);
  EXPECT_EQ(f->reply_delay.count(), 300);
  EXPECT_FALSE(f->to_amplifier);
  EXPECT_TRUE(f->to_biometrics);
  EXPECT_DOUBLE_EQ(f->at_seconds, 1.5);
  f = parse_fault("slow=40", nullptr);
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->to_amplifier && f->to_biometrics);
  EXPECT_DOUBLE_EQ(f->at_seconds, 0.0);
  f = parse_fault("hang-after=2", nullptr);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->kind, FaultAction::Kind::hang);
  EXPECT_DOUBLE_EQ(f->at_seconds, 2.0);
  EXPECT_TRUE(f->to_biometrics);
  EXPECT_FALSE(f->to_amplifier);
  f = parse_fault("hang-after=0:amp", nullptr);
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->to_amplifier);
  EXPECT_FALSE(f->to_biometrics);
}

TEST(FaultSpec, MalformedSpecsSayWhy) {
  for (const char* bad : {"", "disconnect-after", "disconnect-after=-1", "disconnect-after=x",
                          "exception=99", "exception=busy:lamp", "stale-after=1:both",
                          "amp-fault-after=1", "amp-fault-after=1:0", "amp-fault-after=1:smoke",
                          "amp-fault-after=1:0x100", "slow=0", "slow=65536", "slow=fast", "slow=10:lamp",
                          "slow=10@soon", "hang-after=x", "hang-after=1:both", "meltdown=1"}) {
    std::string error;
    EXPECT_FALSE(parse_fault(bad, &error)) << bad;
    EXPECT_NE(error.find("--fault"), std::string::npos) << bad;
  }
}

}  // namespace
}  // namespace knoblab::modbus
