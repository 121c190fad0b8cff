// hapticd's cycle in simulated time (knoblab simulate, design render, the
// in-process study apparatus): the core sees the simulated DAQ's failures
// as the daemon's core sees a real DAQ's.
#include <gtest/gtest.h>

#include "core_harness.hpp"
#include "knoblab/hapticd/sim_time_loop.hpp"
#include "knoblab/hapticd/supervisor.hpp"

namespace knoblab::hapticd {
namespace {

using testing::plant_with;

std::uint32_t faults_after(SimTimeLoop& loop, int cycles) {
  std::uint32_t faults = 0;
  for (int i = 0; i < cycles; ++i) faults = loop.step().faults;
  return faults;
}

TEST(SimTimeLoop, AHealthyLoopRunsWithoutFaultsAndCountsItsCycles) {
  SimTimeLoop loop(plant_with("moderate-detents"), 10000.0);
  EXPECT_EQ(faults_after(loop, 1000), 0u);
  EXPECT_EQ(loop.step().seq, 1000u);
}

TEST(SimTimeLoop, WritesThatFailCyclesRunningLatchTheIoFaultAsInTheDaemon) {
  SimTimeLoop loop(plant_with("moderate-detents"), 10000.0);
  ASSERT_EQ(faults_after(loop, 10), 0u);
  loop.daq().set_write_failure(true);
  const int latch = SafetyLimits{}.max_consecutive_io_errors;
  EXPECT_EQ(faults_after(loop, latch) & kFaultIo, 0u) << "the first failed write shows in the next cycle";
  EXPECT_NE(faults_after(loop, 1) & kFaultIo, 0u);
}

TEST(SimTimeLoop, ReadsThatFailCyclesRunningLatchTheIoFault) {
  SimTimeLoop loop(plant_with("moderate-detents"), 10000.0);
  loop.daq().set_read_failure(true);
  EXPECT_NE(faults_after(loop, SafetyLimits{}.max_consecutive_io_errors) & kFaultIo, 0u);
}

}  // namespace
}  // namespace knoblab::hapticd
