// JSON export of timing figures, for the bench and the daemon's status
// endpoint. Allocates: call it on a snapshot, never inside the loop.
#pragma once

#include <string>

#include "knoblab/rt/timing_stats.hpp"

namespace knoblab::rt {

// {"period_ns":…, "cycles":…, "overruns":…, "max_consecutive_overruns":…,
//  "wakeup_latency":{count,min_ns,max_ns,mean_ns,median_ns,p99_ns,p999_ns,overflow},
//  "compute_time":{…}}; figures of an empty histogram are null.
std::string to_json(const TimingSummary& summary);

// As above; with_bins adds each histogram's non-empty bins as
// "bins":{"bin_ns":W,"counts":[[lower_edge_ns,count],…],"overflow":N}.
std::string to_json(const TimingStats& stats, bool with_bins = false);

}  // namespace knoblab::rt
