#include "knoblab/hal/memory_lines.hpp"

#include <thread>

#include <gtest/gtest.h>

namespace knoblab::hal {
namespace {

DigitalInputs read(MemoryLines& lines) {
  DigitalInputs in;
  EXPECT_EQ(lines.read(in), capture::IoStatus::ok);
  return in;
}

TEST(MemoryLines, StartsWithEstopAssertedLikeAnUnpluggedCable) {
  MemoryLines lines;
  EXPECT_TRUE(read(lines).estop);
}

TEST(MemoryLines, EstopIsActiveLow) {
  MemoryLines lines;
  lines.set_estop_level(true);  // healthy chain holds ESTOP_N high
  EXPECT_FALSE(read(lines).estop);
  lines.set_estop_level(false);  // physical low = e-stop asserted
  EXPECT_TRUE(read(lines).estop);
  lines.release_estop();
  EXPECT_FALSE(read(lines).estop);
  lines.press_estop();
  EXPECT_TRUE(read(lines).estop);
}

TEST(MemoryLines, CanStartReleased) {
  MemoryLines lines(/*estop_asserted=*/false);
  EXPECT_FALSE(read(lines).estop);
}

TEST(MemoryLines, CountsEachButtonPressOnceOnItsEdge) {
  MemoryLines lines;
  EXPECT_EQ(read(lines).capture_presses, 0u);
  lines.press_capture_button();
  lines.press_capture_button();  // still held: no new edge
  DigitalInputs in = read(lines);
  EXPECT_TRUE(in.capture_button);
  EXPECT_EQ(in.capture_presses, 1u);
  lines.release_capture_button();
  in = read(lines);
  EXPECT_FALSE(in.capture_button);
  EXPECT_EQ(in.capture_presses, 1u);
  lines.click_capture_button();
  lines.click_capture_button();
  EXPECT_EQ(read(lines).capture_presses, 3u);
}

TEST(MemoryLines, TestSideSeesWhatTheLoopWrote) {
  MemoryLines lines;
  EXPECT_FALSE(lines.amp_enable());
  EXPECT_FALSE(lines.status_led());
  EXPECT_EQ(lines.write({.amp_enable = true, .status_led = false}), capture::IoStatus::ok);
  EXPECT_TRUE(lines.amp_enable());
  EXPECT_FALSE(lines.status_led());
  EXPECT_EQ(lines.write({.amp_enable = false, .status_led = true}), capture::IoStatus::ok);
  EXPECT_FALSE(lines.amp_enable());
  EXPECT_TRUE(lines.status_led());
  EXPECT_EQ(lines.writes(), 2u);
}

TEST(MemoryLines, AFailedReadReportsEstopAndCountsAnError) {
  MemoryLines lines(false);
  lines.set_read_failure(true);
  DigitalInputs in;
  in.estop = false;
  EXPECT_EQ(lines.read(in), capture::IoStatus::error);
  EXPECT_TRUE(in.estop);
  EXPECT_EQ(lines.io_errors(), 1u);
  lines.set_read_failure(false);
  EXPECT_FALSE(read(lines).estop);
  EXPECT_EQ(lines.io_errors(), 1u);
}

TEST(MemoryLines, PressesFromAnotherThreadAreAllSeenByTheLoop) {
  MemoryLines lines(false);
  constexpr int kPresses = 1000;
  std::thread operator_thread([&] {
    for (int i = 0; i < kPresses; ++i) lines.click_capture_button();
  });
  DigitalInputs in;
  while (in.capture_presses < kPresses) (void)lines.read(in);  // the loop polling
  operator_thread.join();
  EXPECT_EQ(in.capture_presses, static_cast<std::uint64_t>(kPresses));
}

}  // namespace
}  // namespace knoblab::hal
