// PeriodicLoop behaviour. Timing figures are printed, never asserted
// (this host is not realtime); only bounds that hold on any Linux are.
#include <gtest/gtest.h>
#include <sched.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "knoblab/rt/periodic_loop.hpp"
#include "knoblab/rt/stats_json.hpp"

using namespace knoblab::rt;

namespace {
LoopConfig quick(double rate_hz, std::int64_t cycles) {
  LoopConfig c;
  c.rate_hz = rate_hz;
  c.max_cycles = cycles;
  c.lock_memory = false;  // keeps the test process small; one test locks
  return c;
}

void busy_until(std::int64_t t_ns) {
  while (now() < t_ns) {
  }
}
}  // namespace

TEST(PeriodicLoop, RunsExactlyMaxCyclesWithConsecutiveIndices) {
  std::array<std::int64_t, 64> seen{};
  std::int64_t calls = 0;
  std::atomic<bool> stop{false};
  const LoopResult r = run(quick(2000, 50), [&](const CycleInfo& info) {
    if (calls < 64) seen[std::size_t(calls)] = info.index;
    ++calls;
    return true;
  }, stop);
  EXPECT_EQ(calls, 50);
  EXPECT_EQ(r.stats.cycles, 50U);
  EXPECT_EQ(r.stop_reason, StopReason::max_cycles);
  for (std::int64_t i = 0; i < 50; ++i) EXPECT_EQ(seen[std::size_t(i)], i);
}

TEST(PeriodicLoop, ZeroMaxCyclesRunsNothing) {
  std::int64_t calls = 0;
  std::atomic<bool> stop{false};
  const LoopResult r = run(quick(1000, 0), [&](const CycleInfo&) { ++calls; }, stop);
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(r.stop_reason, StopReason::max_cycles);
}

TEST(PeriodicLoop, StopsWhenTheStopFlagIsSet) {
  std::int64_t calls = 0;
  std::atomic<bool> stop{false};
  const LoopResult r = run(quick(2000, -1), [&](const CycleInfo& info) {
    ++calls;
    if (info.index == 20) stop = true;  // seen before the next cycle
  }, stop);
  EXPECT_EQ(calls, 21);
  EXPECT_EQ(r.stop_reason, StopReason::stop_requested);
}

TEST(PeriodicLoop, StopsWhenAnotherThreadSetsStop) {
  std::atomic<bool> stop{false};
  std::atomic<std::int64_t> calls{0};
  std::thread stopper([&] {
    while (calls.load() < 10) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    stop = true;
  });
  const LoopResult r = run(quick(1000, -1), [&](const CycleInfo&) { calls.fetch_add(1); }, stop);
  stopper.join();
  EXPECT_EQ(r.stop_reason, StopReason::stop_requested);
  EXPECT_GE(calls.load(), 10);
  EXPECT_EQ(r.stats.cycles, std::uint64_t(calls.load()));
}

TEST(PeriodicLoop, StopsWhenTheCycleReturnsFalse) {
  std::int64_t calls = 0;
  std::atomic<bool> stop{false};
  const LoopResult r = run(quick(2000, 1000), [&](const CycleInfo& info) {
    ++calls;
    return info.index < 9;
  }, stop);
  EXPECT_EQ(calls, 10);
  EXPECT_EQ(r.stats.cycles, 10U);
  EXPECT_EQ(r.stop_reason, StopReason::cycle_returned_false);
}

TEST(PeriodicLoop, FreeRunDoesNotSleep) {
  LoopConfig c = quick(10, 10'000);  // paced, this would take 1000 s
  c.free_run = true;
  std::atomic<bool> stop{false};
  std::int64_t calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const LoopResult r = run(c, [&](const CycleInfo& info) {
    ++calls;
    EXPECT_EQ(info.deadline_ns, info.now_ns);
  }, stop);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(calls, 10'000);
  EXPECT_LT(ms, 100.0);
  EXPECT_EQ(r.stats.wakeup.count, 0U);  // no deadlines, no latency
  EXPECT_EQ(r.stats.compute.count, 10'000U);
  std::printf("[ figures  ] 10000 free-run cycles in %.2f ms\n", ms);
}

TEST(PeriodicLoop, PacedModeKeepsTheAverageRate) {
  std::atomic<bool> stop{false};
  std::int64_t early = 0, last_deadline = 0, non_increasing = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const LoopResult r = run(quick(1000, 200), [&](const CycleInfo& info) {
    early += info.now_ns < info.deadline_ns;  // clock_nanosleep never returns early
    non_increasing += info.deadline_ns <= last_deadline;
    last_deadline = info.deadline_ns;
  }, stop);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(ms, 199.0);
  EXPECT_EQ(early, 0);
  EXPECT_EQ(non_increasing, 0);
  EXPECT_EQ(r.stats.wakeup.count, 200U);
  EXPECT_EQ(r.stats.period_ns, 1'000'000);
  std::printf("[ figures  ] 200 cycles at 1 kHz in %.1f ms; %s\n", ms, to_json(summarize(r.stats)).c_str());
}

TEST(PeriodicLoop, OverrunIsCountedAndTheScheduleReanchored) {
  std::atomic<bool> stop{false};
  std::array<CycleInfo, 12> infos{};
  std::int64_t stall_end = 0;
  const LoopResult r = run(quick(1000, 12), [&](const CycleInfo& info) {
    infos[std::size_t(info.index)] = info;
    if (info.index == 5) {
      stall_end = info.now_ns + 3'500'000;  // 3.5 periods of work
      busy_until(stall_end);
    }
  }, stop);
  EXPECT_GE(r.stats.overruns, 1U);
  EXPECT_GE(r.stats.max_consecutive_overruns, 1U);
  EXPECT_GE(infos[6].consecutive_overruns, 1);
  // Re-anchored: cycle 6 is due after the stall, not at the missed slots
  // (no burst of cycles with deadlines in the past).
  EXPECT_GE(infos[6].deadline_ns, stall_end);
  EXPECT_GE(infos[7].deadline_ns, infos[6].deadline_ns + infos[6].period_ns);
  std::printf("[ figures  ] overruns %llu; consecutive before cycle 7: %lld\n",
              static_cast<unsigned long long>(r.stats.overruns),
              static_cast<long long>(infos[7].consecutive_overruns));
}

TEST(PeriodicLoop, VoidCycleRunsUntilMaxCycles) {
  std::atomic<bool> stop{false};
  int calls = 0;
  const LoopResult r = run(quick(5000, 7), [&](const CycleInfo&) { ++calls; }, stop);
  EXPECT_EQ(calls, 7);
  EXPECT_EQ(r.stop_reason, StopReason::max_cycles);
}

TEST(PeriodicLoop, InvalidConfigurationsAreRejected) {
  std::atomic<bool> stop{false};
  for (double rate : {0.0, 0.5, -10.0, 20000.5, 1e9, std::nan(""),
                      std::numeric_limits<double>::infinity()}) {
    LoopConfig c = quick(rate, 1);
    EXPECT_THROW(validate(c), std::invalid_argument) << rate;
    bool ran = false;
    EXPECT_THROW(run(c, [&](const CycleInfo&) { ran = true; }, stop), std::invalid_argument) << rate;
    EXPECT_FALSE(ran);
  }
  EXPECT_NO_THROW(validate(quick(1.0, 1)));
  EXPECT_NO_THROW(validate(quick(20000.0, 1)));
  auto bad = [](auto tweak) {
    LoopConfig c = quick(1000, 1);
    tweak(c);
    return c;
  };
  EXPECT_THROW(validate(bad([](LoopConfig& c) { c.priority = 0; })), std::invalid_argument);
  EXPECT_THROW(validate(bad([](LoopConfig& c) { c.priority = 100; })), std::invalid_argument);
  EXPECT_THROW(validate(bad([](LoopConfig& c) { c.cpu = -2; })), std::invalid_argument);
  EXPECT_THROW(validate(bad([](LoopConfig& c) { c.max_cycles = -2; })), std::invalid_argument);
  EXPECT_THROW(validate(bad([](LoopConfig& c) { c.publish_every = 0; })), std::invalid_argument);
}

TEST(PeriodicLoop, ReportedRealtimeStatusMatchesTheCycleThread) {
  LoopConfig c = quick(1000, 5);
  c.lock_memory = true;
  std::atomic<bool> stop{false};
  int policy = -1;
  const LoopResult r = run(c, [&](const CycleInfo&) { policy = sched_getscheduler(0); }, stop);
  EXPECT_EQ(r.realtime, policy == SCHED_FIFO);
  EXPECT_EQ(r.realtime, r.realtime_status.realtime());
  if (!r.realtime) {
    EXPECT_FALSE(r.warnings.empty());
  } else if (r.memory_status.ok()) {
    EXPECT_TRUE(r.warnings.empty());
  }
  std::printf("[ figures  ] realtime=%d memory=%s warnings=%zu\n", int(r.realtime),
              r.memory_status.message().c_str(), r.warnings.size());
}

TEST(PeriodicLoop, FailedPinningIsAWarningUnlessRealtimeIsRequired) {
  LoopConfig c = quick(1000, 3);
  c.cpu = CPU_SETSIZE - 1;  // valid number, missing CPU: pthread_setaffinity_np fails
  std::atomic<bool> stop{false};
  int calls = 0;
  const LoopResult r = run(c, [&](const CycleInfo&) { ++calls; }, stop);
  EXPECT_EQ(calls, 3);
  EXPECT_FALSE(r.realtime_status.affinity.ok());
  ASSERT_FALSE(r.warnings.empty());

  c.require_realtime = true;
  calls = 0;
  EXPECT_THROW(run(c, [&](const CycleInfo&) { ++calls; }, stop), std::system_error);
  EXPECT_EQ(calls, 0) << "no cycle may run when required realtime settings failed";
}

TEST(PeriodicLoop, ExceptionFromTheCycleReachesTheCaller) {
  std::atomic<bool> stop{false};
  int calls = 0;
  EXPECT_THROW(run(quick(2000, 100), [&](const CycleInfo& info) {
    ++calls;
    if (info.index == 3) throw std::runtime_error("cycle failed");
  }, stop), std::runtime_error);
  EXPECT_EQ(calls, 4);
}

TEST(PeriodicLoop, PublishesConsistentStatsWhileRunning) {
  auto publisher = std::make_unique<StatsPublisher>();
  LoopConfig c = quick(2000, 400);
  c.publish_every = 10;
  std::atomic<bool> stop{false}, done{false};
  std::uint64_t reads = 0, inconsistent = 0, max_seen = 0;
  std::thread monitor([&] {
    auto snap = std::make_unique<TimingStats>();
    for (;;) {
      const bool last = done.load();  // one more read after the loop has ended
      *snap = publisher->read();
      ++reads;
      inconsistent += snap->cycles % 10 != 0 || snap->wakeup.count != snap->cycles ||
                      snap->compute.count != snap->cycles;
      if (snap->cycles > max_seen) max_seen = snap->cycles;
      if (last) break;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  const LoopResult r = run(c, [](const CycleInfo&) {}, stop, publisher.get());
  done = true;
  monitor.join();
  EXPECT_EQ(inconsistent, 0U);
  EXPECT_EQ(publisher->version(), 400U / 10 + 1);  // periodic ones plus the final one
  EXPECT_EQ(publisher->read().cycles, r.stats.cycles);
  EXPECT_EQ(max_seen, 400U);
  std::printf("[ figures  ] monitor took %llu snapshots\n", static_cast<unsigned long long>(reads));
}
