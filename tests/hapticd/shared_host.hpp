// Daemon tests run the real paced 10 kHz loop on a shared, non-realtime test
// host, where a compute-heavy neighbour can make many cycles in a row late.
// There the loop's lateness is reported, not a test failure ("never gate CI
// on latency"): the overrun policy itself is tested with synthetic counts in
// supervisor_test.cpp, and everything else these tests check (samples, store,
// faults from the lines and Modbus) does not depend on when a cycle ran.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>

#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/rt/timing_stats.hpp"

namespace knoblab::hapticd::shared_host {

inline void configure(DaemonConfig& cfg) {
  cfg.loop.lock_memory = false;
  cfg.core.limits.max_consecutive_overruns = std::numeric_limits<int>::max();
}

// One line in the running test's log: how late the loop ran on this host.
inline void report_timing(const rt::LoopResult& r) {
  const char* test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const rt::TimingSummary s = rt::summarize(r.stats);
  std::printf("[ timing   ] %s: %s, %llu cycles, %llu overruns (at most %llu in a row), "
              "wake-up p99 %.0f us, max %.0f us\n",
              test, r.realtime ? "SCHED_FIFO" : "not realtime", static_cast<unsigned long long>(s.cycles),
              static_cast<unsigned long long>(s.overruns),
              static_cast<unsigned long long>(s.max_consecutive_overruns), static_cast<double>(s.wakeup.p99_ns) * 1e-3,
              static_cast<double>(s.wakeup.max_ns) * 1e-3);
}

}  // namespace knoblab::hapticd::shared_host
