// PeriodicLoop (libfranka style): run() owns the realtime thread. It starts
// the thread, makes it realtime, then per cycle:
//   sleep to the absolute deadline → note wake-up latency → cycle(info) →
//   note compute time → detect overrun → every N cycles publish stats,
// and returns, thread joined, with the final TimingStats.
//
// The realtime contract: after the thread is set up the loop machinery does
// not allocate, lock, log or throw; the cycle callable must not either (it
// runs on the realtime thread; tests/rt/test_loop_alloc.cpp checks the loop).
// Overruns are reported in CycleInfo::consecutive_overruns, so the cycle
// itself can decide to go safe — no callbacks.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "knoblab/rt/os.hpp"
#include "knoblab/rt/stats_publisher.hpp"
#include "knoblab/rt/timing_stats.hpp"

namespace knoblab::rt {

struct LoopConfig {
  double rate_hz = 10000.0;      // 1 .. 20000, else run() throws
  int priority = 80;             // SCHED_FIFO priority, 1 .. 99
  int cpu = -1;                  // pin to this CPU; -1: no pinning
  bool lock_memory = true;       // mlockall + stack prefault before the first cycle
  bool free_run = false;         // back to back, no sleeping (benchmarks, simulated time)
  std::int64_t max_cycles = -1;  // -1: until stopped
  // true: every realtime setting asked for (SCHED_FIFO; memory locking and
  // pinning when set) must succeed, else run() throws before the first cycle.
  // false: failures become warnings in the result and the loop runs anyway.
  bool require_realtime = false;
  std::int64_t publish_every = 1000;  // cycles between StatsPublisher snapshots (>= 1)
};

// Throws std::invalid_argument naming the offending field.
void validate(const LoopConfig& config);

// The period for a rate, rounded to whole nanoseconds.
std::int64_t period_ns(double rate_hz) noexcept;

struct CycleInfo {
  std::int64_t index = 0;        // 0, 1, 2, … without gaps
  std::int64_t deadline_ns = 0;  // scheduled start (CLOCK_MONOTONIC); free-run: = now_ns
  std::int64_t now_ns = 0;       // when the cycle actually started
  std::int64_t period_ns = 0;
  // Overruns in a row right before this cycle (0: the last cycle was on
  // time). The owner's policy hook: e.g. go safe when it exceeds a limit.
  std::int64_t consecutive_overruns = 0;
};

enum class StopReason {
  stop_requested,        // the stop flag was set
  max_cycles,            // LoopConfig::max_cycles cycles ran
  cycle_returned_false,  // the cycle asked to stop
  sleep_failed,          // clock_nanosleep failed; see LoopResult::sleep_status
};
const char* to_string(StopReason reason) noexcept;

struct LoopResult {
  TimingStats stats;
  StopReason stop_reason = StopReason::stop_requested;
  bool realtime = false;           // the loop thread ran under SCHED_FIFO
  RealtimeStatus realtime_status;  // outcome of set_thread_realtime
  Status memory_status;            // outcome of lock_memory (ok when not asked)
  Status sleep_status;             // set when stop_reason == sleep_failed
  std::vector<std::string> warnings;  // realtime settings that failed (built after the join)
};

namespace detail {

// What the loop thread reports back; written by it, read after the join.
struct ThreadReport {
  RealtimeStatus realtime_status;
  Status memory_status;
  Status sleep_status;
  bool realtime = false;
  bool ran = false;  // false: require_realtime failed, no cycle ran
  StopReason stop_reason = StopReason::stop_requested;
  TimingStats stats;
  std::exception_ptr error;  // thrown by the cycle
};

// Locks memory and makes the calling thread realtime as the config asks;
// records the outcomes; false when require_realtime is set and one failed.
bool enter_realtime(const LoopConfig& config, ThreadReport& report) noexcept;

// Runs body(arg) on a new thread (pthread_create, so Xenomai's wrapper makes
// it a Cobalt thread) and joins it. Throws std::system_error if it cannot start.
void run_on_thread(void (*body)(void*), void* arg);

// Turns a report into the result: warnings, or the exception when
// require_realtime failed or the cycle threw.
LoopResult finish(const LoopConfig& config, ThreadReport& report);

template <class Cycle>
bool invoke_cycle(Cycle& cycle, const CycleInfo& info) {
  if constexpr (std::is_void_v<std::invoke_result_t<Cycle&, const CycleInfo&>>) {
    std::invoke(cycle, info);
    return true;
  } else {
    return static_cast<bool>(std::invoke(cycle, info));
  }
}

// The loop proper. Everything it touches exists before the first cycle.
template <class Cycle>
StopReason loop(const LoopConfig& config, Cycle& cycle, std::atomic<bool>& stop,
                StatsPublisher* publisher, TimingStats& stats, Status& sleep_status) noexcept(
    std::is_nothrow_invocable_v<Cycle&, const CycleInfo&>) {
  const std::int64_t period = period_ns(config.rate_hz);
  stats.period_ns = period;
  std::int64_t consecutive = 0;
  std::int64_t deadline = now() + period;
  for (std::int64_t index = 0;; ++index) {
    if (config.max_cycles >= 0 && index >= config.max_cycles) return StopReason::max_cycles;
    if (stop.load(std::memory_order_acquire)) return StopReason::stop_requested;

    std::int64_t woke;
    if (config.free_run) {
      woke = now();
      deadline = woke;
    } else {
      if (Status s = sleep_until(deadline); !s.ok()) {
        sleep_status = s;
        return StopReason::sleep_failed;
      }
      woke = now();
      stats.wakeup.record(woke - deadline);
    }

    const bool go = invoke_cycle(cycle, CycleInfo{index, deadline, woke, period, consecutive});
    const std::int64_t done = now();
    stats.compute.record(done - woke);
    ++stats.cycles;

    if (!config.free_run) {
      deadline += period;
      if (done > deadline) {
        // Missed the next deadline: count it and re-anchor the schedule at
        // `done` (the next cycle starts at once, later ones a period apart)
        // rather than catching up with a burst of back-to-back cycles.
        ++stats.overruns;
        ++consecutive;
        if (static_cast<std::uint64_t>(consecutive) > stats.max_consecutive_overruns)
          stats.max_consecutive_overruns = static_cast<std::uint64_t>(consecutive);
        deadline = done;
      } else {
        consecutive = 0;
      }
    }
    if (publisher != nullptr && stats.cycles % static_cast<std::uint64_t>(config.publish_every) == 0)
      publisher->publish(stats);
    if (!go) return StopReason::cycle_returned_false;
  }
}

}  // namespace detail

// Runs `cycle` periodically on a realtime thread until `stop` is set,
// max_cycles have run, or the cycle returns false (a cycle returning void
// runs on). Blocks until the thread has joined. `cycle` is invoked as
// cycle(const CycleInfo&) and must not allocate, lock or block. When
// `publisher` is given, snapshots go there every publish_every cycles and at
// the end. Throws std::invalid_argument for a bad config, std::system_error
// when require_realtime cannot be met, and rethrows what the cycle threw.
template <class Cycle>
LoopResult run(const LoopConfig& config, Cycle&& cycle, std::atomic<bool>& stop,
               StatsPublisher* publisher = nullptr) {
  using Fn = std::remove_reference_t<Cycle>;
  static_assert(std::is_invocable_v<Fn&, const CycleInfo&>,
                "cycle must be callable as cycle(const CycleInfo&)");
  validate(config);

  struct Context {
    const LoopConfig* config;
    Fn* cycle;
    std::atomic<bool>* stop;
    StatsPublisher* publisher;
    detail::ThreadReport report;
  };
  Context ctx{&config, &cycle, &stop, publisher, {}};

  detail::run_on_thread(
      [](void* arg) {
        auto& c = *static_cast<Context*>(arg);
        if (!detail::enter_realtime(*c.config, c.report)) return;
        c.report.ran = true;
        try {
          c.report.stop_reason = detail::loop(*c.config, *c.cycle, *c.stop, c.publisher,
                                              c.report.stats, c.report.sleep_status);
        } catch (...) {
          c.report.error = std::current_exception();
        }
        if (c.publisher != nullptr) c.publisher->publish(c.report.stats);
      },
      &ctx);
  return detail::finish(config, ctx.report);
}

}  // namespace knoblab::rt
