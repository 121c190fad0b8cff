// What the UI derives from hapticd's replies: the measured loop rate and the
// status strip's reading of the fault list.
#include <gtest/gtest.h>

#include "daemon_state.hpp"

namespace knoblab::ui {
namespace {

TEST(LoopRateMeter, TheRateIsTheCyclesCountedOverTheTimeBetweenReadings) {
  LoopRateMeter m;
  EXPECT_FALSE(m.update(1000, 10.0).has_value());  // one reading says nothing yet
  const auto r = m.update(1200, 10.2);             // 200 cycles in 0.2 s
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, 1000.0, 1e-9);
}

TEST(LoopRateMeter, ReadingsCloserThanATenthOfASecondWaitForALaterOne) {
  LoopRateMeter m;
  m.update(0, 0.0);
  EXPECT_FALSE(m.update(50, 0.05).has_value());
  const auto r = m.update(150, 0.15);  // measured over the whole 0.15 s
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(*r, 1000.0, 1e-9);
}

TEST(LoopRateMeter, ASlowerLoopPullsTheEstimateDownWithinAboutASecond) {
  LoopRateMeter m;
  m.update(0, 0.0);
  m.update(1000, 1.0);  // 1 kHz
  double t = 1.0;
  std::uint64_t cycles = 1000;
  std::optional<double> r;
  for (int k = 0; k < 10; ++k) {  // then 500 Hz for 2 s
    t += 0.2, cycles += 100;
    r = m.update(cycles, t);
  }
  ASSERT_TRUE(r.has_value());
  EXPECT_LT(*r, 570.0);
  EXPECT_GT(*r, 500.0);
}

TEST(LoopRateMeter, ACounterThatGoesBackMeansARestartedDaemonAndStartsOver) {
  LoopRateMeter m;
  m.update(0, 0.0);
  ASSERT_TRUE(m.update(1000, 1.0).has_value());
  EXPECT_FALSE(m.update(10, 1.2).has_value());
  EXPECT_NEAR(*m.update(210, 1.4), 1000.0, 1e-9);
}

TEST(FaultReading, EstopAndTheAmplifierAreReadApartFromTheOtherFaults) {
  const FaultReading r = read_faults({"estop", "amp_comms", "velocity"});
  EXPECT_TRUE(r.estop);
  EXPECT_TRUE(r.amplifier);
  EXPECT_EQ(r.others, std::vector<std::string>{"velocity"});
  const FaultReading none = read_faults({});
  EXPECT_FALSE(none.estop || none.amplifier);
}

TEST(ModbusReading, ARunningPollerIsOkItsProblemsAreSaidInWordsAndNoPollerIsOff) {
  EXPECT_EQ(read_modbus("running").text, "ok");
  EXPECT_TRUE(read_modbus("running|amp-enabled").ok);
  const ModbusReading bad = read_modbus("running|amp-comms-lost|biometrics-stale");
  EXPECT_FALSE(bad.ok);
  EXPECT_EQ(bad.text, "amp comms lost, biometrics stale");
  EXPECT_EQ(read_modbus("ok").text, "off");
  EXPECT_TRUE(read_modbus("ok").ok);
}

}  // namespace
}  // namespace knoblab::ui
