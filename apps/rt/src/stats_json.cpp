// Hand-formatted JSON: only numbers and fixed keys, so no escaping needed.
#include "knoblab/rt/stats_json.hpp"

#include <format>
#include <span>

namespace knoblab::rt {

namespace {

void append_summary(std::string& out, const HistogramSummary& s) {
  out += std::format("{{\"count\":{}", s.count);
  if (s.count == 0) {
    out += ",\"min_ns\":null,\"max_ns\":null,\"mean_ns\":null,\"median_ns\":null,"
           "\"p99_ns\":null,\"p999_ns\":null";
  } else {
    out += std::format(
        ",\"min_ns\":{},\"max_ns\":{},\"mean_ns\":{:.1f},\"median_ns\":{},\"p99_ns\":{},"
        "\"p999_ns\":{}",
        s.min_ns, s.max_ns, s.mean_ns, s.median_ns, s.p99_ns, s.p999_ns);
  }
  out += std::format(",\"overflow\":{}", s.overflow);
}

void append_bins(std::string& out, std::span<const std::uint64_t> bins, std::int64_t bin_ns) {
  out += std::format(",\"bins\":{{\"bin_ns\":{},\"counts\":[", bin_ns);
  bool first = true;
  for (std::size_t b = 0; b + 1 < bins.size(); ++b) {
    if (bins[b] == 0) continue;
    out += std::format("{}[{},{}]", first ? "" : ",", static_cast<std::int64_t>(b) * bin_ns, bins[b]);
    first = false;
  }
  out += std::format("],\"overflow\":{}}}", bins.empty() ? 0 : bins.back());
}

void append_header(std::string& out, const TimingSummary& s) {
  out += std::format(
      "{{\"period_ns\":{},\"cycles\":{},\"overruns\":{},\"max_consecutive_overruns\":{}",
      s.period_ns, s.cycles, s.overruns, s.max_consecutive_overruns);
}

}  // namespace

std::string to_json(const TimingSummary& summary) {
  std::string out;
  append_header(out, summary);
  out += ",\"wakeup_latency\":";
  append_summary(out, summary.wakeup);
  out += "},\"compute_time\":";
  append_summary(out, summary.compute);
  out += "}}";
  return out;
}

std::string to_json(const TimingStats& stats, bool with_bins) {
  const TimingSummary summary = summarize(stats);
  std::string out;
  append_header(out, summary);
  out += ",\"wakeup_latency\":";
  append_summary(out, summary.wakeup);
  if (with_bins) append_bins(out, stats.wakeup.bins(), WakeupHistogram::kBinNs);
  out += "},\"compute_time\":";
  append_summary(out, summary.compute);
  if (with_bins) append_bins(out, stats.compute.bins(), ComputeHistogram::kBinNs);
  out += "}}";
  return out;
}

}  // namespace knoblab::rt
