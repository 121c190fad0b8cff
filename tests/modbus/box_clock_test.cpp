// BoxClock: samples keep the box's spacing on the host clock however late the
// polls that read them ran.
#include <gtest/gtest.h>

#include "knoblab/modbus/box_clock.hpp"

namespace knoblab::modbus {
namespace {

using namespace std::chrono_literals;
using Clock = BoxClock::Clock;

// The box starts its clock 5 s after the host's epoch; a sample taken at box
// time b is on the host clock at 5 s + b.
constexpr auto kBoxStart = 5s;
Clock::time_point host(std::uint32_t box_ms) { return Clock::time_point(kBoxStart + std::chrono::milliseconds(box_ms)); }

TEST(BoxClock, ALatePollDoesNotBunchTheSamplesItFinds) {
  BoxClock clock;
  // Polls every 10 ms, each 2 ms after the newest sample; then one poll runs
  // 70 ms late and finds three samples at once.
  clock.observe(0, host(0) + 2ms);
  clock.observe(31, host(31) + 2ms);
  clock.observe(125, host(125) + 70ms);  // 62, 93 and 125 found late together
  for (std::uint32_t b : {62u, 93u, 125u}) {
    const auto taken = clock.to_host(b);
    EXPECT_EQ(taken, host(b) + 2ms) << b;  // the least-delayed poll's offset
    EXPECT_LE(taken, host(125) + 70ms);    // never after it was received
  }
  EXPECT_EQ(clock.to_host(93) - clock.to_host(62), 31ms);  // the box's own spacing
}

TEST(BoxClock, AQuickerPollImprovesTheEstimate) {
  BoxClock clock;
  clock.observe(0, host(0) + 40ms);  // the first poll ran late
  EXPECT_EQ(clock.to_host(0), host(0) + 40ms);
  clock.observe(31, host(31) + 1ms);
  EXPECT_EQ(clock.to_host(31), host(31) + 1ms);
  EXPECT_EQ(clock.to_host(0), host(0) + 1ms);
}

TEST(BoxClock, TheEstimateForgetsPollsOlderThanTheWindow) {
  // The host clock runs 1 ms per second faster than the box's (a big drift,
  // to see it): the offset grows, and the estimate must follow it rather
  // than keep the first poll's minimum forever.
  BoxClock clock(4s);
  auto received = [](std::uint32_t b) { return host(b) + std::chrono::microseconds(b) + 2ms; };
  for (std::uint32_t b = 0; b <= 20000; b += 31) clock.observe(b, received(b));
  const std::uint32_t now = 20000 - 20000 % 31;
  const auto error = received(now) - 2ms - clock.to_host(now);  // true drift-corrected offset vs estimate
  EXPECT_GE(error, 0ms);
  EXPECT_LE(error, 4ms + 1ms);  // at most a window's drift old, not 20 ms
}

TEST(BoxClock, ABoxClockGoingBackwardsStartsOver) {
  BoxClock clock;
  clock.observe(100000, host(100000) + 1ms);
  // The box restarted: its clock begins again at 0, and the host is 3 s on.
  const auto restarted = host(100000) + 3s;
  clock.observe(0, restarted + 2ms);
  EXPECT_EQ(clock.to_host(0), restarted + 2ms);
}

}  // namespace
}  // namespace knoblab::modbus
