// Fixed-bin histogram recorded inside the realtime loop: one array index and
// a few adds per sample, no allocation. Quantiles
// are read later, outside the loop, from a copy (see timing_stats.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace knoblab::rt {

// Bins bins of BinNs nanoseconds each, [0, BinNs), [BinNs, 2 BinNs), …, then
// one overflow bin for everything >= Bins * BinNs. Negative values (a clock
// oddity, never expected) land in bin 0 but still count towards min.
// All members are 8-byte integers so a snapshot copies as whole words.
template <std::int64_t BinNs, std::size_t Bins>
struct Histogram {
  static_assert(BinNs > 0 && Bins > 0);
  static constexpr std::int64_t kBinNs = BinNs;
  static constexpr std::size_t kBins = Bins;

  std::uint64_t counts[Bins + 1] = {};  // counts[Bins] is the overflow bin
  std::uint64_t count = 0;
  std::int64_t sum_ns = 0;  // 2^63 ns is 292 years of summed samples
  std::int64_t min_ns = std::numeric_limits<std::int64_t>::max();
  std::int64_t max_ns = std::numeric_limits<std::int64_t>::min();

  void record(std::int64_t ns) noexcept {
    std::size_t bin = 0;
    if (ns > 0) {
      const std::int64_t b = ns / BinNs;
      bin = b >= static_cast<std::int64_t>(Bins) ? Bins : static_cast<std::size_t>(b);
    }
    ++counts[bin];
    ++count;
    sum_ns += ns;
    if (ns < min_ns) min_ns = ns;
    if (ns > max_ns) max_ns = ns;
  }

  std::uint64_t overflow() const noexcept { return counts[Bins]; }
  std::span<const std::uint64_t> bins() const noexcept { return {counts, Bins + 1}; }
};

// What the histogram says, in nanoseconds. Quantiles are upper bounds with
// one bin of resolution: at least that fraction of samples was <= the value
// (the bin's upper edge, capped at the exact max). When `count` is 0 the
// other fields are 0.
struct HistogramSummary {
  std::uint64_t count = 0;
  std::int64_t min_ns = 0;
  std::int64_t max_ns = 0;
  double mean_ns = 0.0;
  std::int64_t median_ns = 0;
  std::int64_t p99_ns = 0;
  std::int64_t p999_ns = 0;
  std::uint64_t overflow = 0;
};

// The q-quantile (0 <= q <= 1) of a histogram given as its bins (last one
// the overflow bin), bin width and exact min/max. q <= 0 gives min, q >= 1
// max; a quantile falling in the overflow bin gives max. 0 when empty.
std::int64_t quantile_ns(std::span<const std::uint64_t> bins, std::int64_t bin_ns,
                         std::int64_t min_ns, std::int64_t max_ns, double q) noexcept;

HistogramSummary summarize(std::span<const std::uint64_t> bins, std::int64_t bin_ns,
                           std::uint64_t count, std::int64_t sum_ns, std::int64_t min_ns,
                           std::int64_t max_ns) noexcept;

// A fine histogram summed into bins whose upper edges double from
// `first_edge_ns` up to the fine range's top: what a display draws on a log
// axis (1, 2, 4 … µs). counts has one entry more than upper_ns: the last is
// everything at or above the last edge, the overflow bin included. A fine
// bin goes whole into the coarse bin holding its upper edge.
struct DoublingBins {
  std::vector<std::int64_t> upper_ns;
  std::vector<std::uint64_t> counts;
};
DoublingBins doubling_bins(std::span<const std::uint64_t> bins, std::int64_t bin_ns, std::int64_t first_edge_ns);

template <std::int64_t BinNs, std::size_t Bins>
std::int64_t quantile_ns(const Histogram<BinNs, Bins>& h, double q) noexcept {
  return quantile_ns(h.bins(), BinNs, h.min_ns, h.max_ns, q);
}

template <std::int64_t BinNs, std::size_t Bins>
HistogramSummary summarize(const Histogram<BinNs, Bins>& h) noexcept {
  return summarize(h.bins(), BinNs, h.count, h.sum_ns, h.min_ns, h.max_ns);
}

}  // namespace knoblab::rt
