// The loop's timing record, kept inside the realtime thread without
// allocation (like cyclictest's histogram): wake-up latency, compute time,
// overruns. Summaries and quantiles are computed outside the loop from a
// copy — the loop publishes copies through a Seqlock (stats_publisher.hpp).
#pragma once

#include <cstdint>
#include <type_traits>

#include "knoblab/rt/histogram.hpp"

namespace knoblab::rt {

// Wake-up latency (actual wake − deadline): 1 µs bins up to 2 ms.
using WakeupHistogram = Histogram<1000, 2000>;
// Compute time (cycle end − wake-up): 50 ns bins up to 100 µs.
using ComputeHistogram = Histogram<50, 2000>;

struct TimingStats {
  std::int64_t period_ns = 0;
  std::uint64_t cycles = 0;
  // A cycle that finished after the next deadline (late wake-up or long compute).
  std::uint64_t overruns = 0;
  std::uint64_t max_consecutive_overruns = 0;
  WakeupHistogram wakeup;  // empty in free-run mode: there are no deadlines
  ComputeHistogram compute;
};
static_assert(std::is_trivially_copyable_v<TimingStats>);
static_assert(sizeof(TimingStats) % sizeof(std::uint64_t) == 0);

struct TimingSummary {
  std::int64_t period_ns = 0;
  std::uint64_t cycles = 0;
  std::uint64_t overruns = 0;
  std::uint64_t max_consecutive_overruns = 0;
  HistogramSummary wakeup;
  HistogramSummary compute;
};

// Not for the loop: walks both histograms (a few µs).
TimingSummary summarize(const TimingStats& stats) noexcept;

}  // namespace knoblab::rt
