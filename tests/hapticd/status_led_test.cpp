// The status LED's patterns (status_led.hpp): steady on when ready, off while
// the motor is held safe, a 2 Hz blink while a capture or calibration records.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "knoblab/hapticd/status_led.hpp"

namespace knoblab::hapticd {
namespace {

TEST(StatusLed, IsSteadyOnWhenIdleOrRendering) {
  for (Mode m : {Mode::Idle, Mode::Render})
    for (std::uint64_t cycle = 0; cycle < 30000; ++cycle)
      ASSERT_TRUE(status_led(false, m, cycle, 10000.0)) << to_string(m) << " cycle " << cycle;
}

TEST(StatusLed, IsOffWhileTheMotorIsHeldSafeWhateverTheMode) {
  for (Mode m : {Mode::Idle, Mode::Render, Mode::Capture, Mode::Calibrate})
    for (std::uint64_t cycle = 0; cycle < 30000; ++cycle)
      ASSERT_FALSE(status_led(true, m, cycle, 10000.0)) << to_string(m) << " cycle " << cycle;
}

// Over two seconds of cycles: the level changes every quarter second, so a
// whole blink takes half a second (2 Hz) at any loop rate, lit half the time.
TEST(StatusLed, BlinksAtTwoHertzWhileACaptureOrCalibrationRecordsAtEitherLoopRate) {
  for (double rate : {10000.0, 2000.0}) {
    for (Mode m : {Mode::Capture, Mode::Calibrate}) {
      SCOPED_TRACE(::testing::Message() << to_string(m) << " at " << rate << " Hz");
      const auto cycles = static_cast<std::uint64_t>(2.0 * rate);
      std::vector<std::uint64_t> changes;
      std::uint64_t lit = 0;
      bool previous = status_led(false, m, 0, rate);
      EXPECT_TRUE(previous) << "a run's first cycle lights the LED";
      for (std::uint64_t c = 0; c < cycles; ++c) {
        const bool now = status_led(false, m, c, rate);
        lit += now;
        if (now != previous) changes.push_back(c);
        previous = now;
      }
      ASSERT_EQ(changes.size(), 7u) << "four blinks in two seconds";
      for (std::size_t i = 0; i < changes.size(); ++i)
        EXPECT_EQ(changes[i], static_cast<std::uint64_t>(rate / 4.0) * (i + 1)) << "change " << i;
      EXPECT_EQ(lit, cycles / 2);
    }
  }
}

TEST(StatusLed, ReadsTheLoopRecordsFlagsModeAndCycleNumber) {
  LoopRecord r;
  r.mode = Mode::Render;
  r.sample.flags = interchange::kAmpEnabled;
  EXPECT_TRUE(status_led(r, 10000.0));
  r.sample.flags = interchange::kFaultLatched;
  EXPECT_FALSE(status_led(r, 10000.0)) << "a latched fault";
  r.sample.flags = interchange::kEstopActive;
  EXPECT_FALSE(status_led(r, 10000.0)) << "the e-stop pressed";
  r.sample.flags = interchange::kAmpEnabled;
  r.mode = Mode::Capture;
  r.seq = 100;  // the first quarter second at 10 kHz: lit
  EXPECT_TRUE(status_led(r, 10000.0));
  r.seq = 3000;  // the second quarter: dark
  EXPECT_FALSE(status_led(r, 10000.0));
}

}  // namespace
}  // namespace knoblab::hapticd
