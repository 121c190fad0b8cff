// How the loop hands its TimingStats to a non-realtime thread: every
// LoopConfig::publish_every cycles (and once at the end) the loop publishes a
// copy; a monitor thread calls read() whenever it likes, then summarize()
// or to_json() on its own copy. The loop never blocks on the reader.
#pragma once

#include "knoblab/rt/seqlock.hpp"
#include "knoblab/rt/timing_stats.hpp"

namespace knoblab::rt {

using StatsPublisher = Seqlock<TimingStats>;

}  // namespace knoblab::rt
