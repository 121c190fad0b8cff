// Quantiles and summaries, computed outside the loop from a snapshot.
#include <cmath>

#include "knoblab/rt/histogram.hpp"
#include "knoblab/rt/timing_stats.hpp"

namespace knoblab::rt {

std::int64_t quantile_ns(std::span<const std::uint64_t> bins, std::int64_t bin_ns,
                         std::int64_t min_ns, std::int64_t max_ns, double q) noexcept {
  std::uint64_t total = 0;
  for (std::uint64_t c : bins) total += c;
  if (total == 0 || bins.empty()) return 0;
  if (!(q > 0.0)) return min_ns;  // also catches NaN
  if (q >= 1.0) return max_ns;
  // The sample of rank ceil(q·n) (1-based) decides the quantile.
  auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  if (rank == 0) rank = 1;
  std::uint64_t seen = 0;
  const std::size_t overflow_bin = bins.size() - 1;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    seen += bins[b];
    if (seen < rank) continue;
    if (b == overflow_bin) return max_ns;
    const std::int64_t upper_edge = (static_cast<std::int64_t>(b) + 1) * bin_ns;
    return upper_edge < max_ns ? upper_edge : max_ns;
  }
  return max_ns;
}

HistogramSummary summarize(std::span<const std::uint64_t> bins, std::int64_t bin_ns,
                           std::uint64_t count, std::int64_t sum_ns, std::int64_t min_ns,
                           std::int64_t max_ns) noexcept {
  HistogramSummary s;
  if (count == 0) return s;
  s.count = count;
  s.min_ns = min_ns;
  s.max_ns = max_ns;
  s.mean_ns = static_cast<double>(sum_ns) / static_cast<double>(count);
  s.median_ns = quantile_ns(bins, bin_ns, min_ns, max_ns, 0.5);
  s.p99_ns = quantile_ns(bins, bin_ns, min_ns, max_ns, 0.99);
  s.p999_ns = quantile_ns(bins, bin_ns, min_ns, max_ns, 0.999);
  s.overflow = bins.empty() ? 0 : bins.back();
  return s;
}

DoublingBins doubling_bins(std::span<const std::uint64_t> bins, std::int64_t bin_ns, std::int64_t first_edge_ns) {
  DoublingBins out;
  if (bins.empty() || bin_ns <= 0 || first_edge_ns <= 0) return out;
  const std::int64_t top = static_cast<std::int64_t>(bins.size() - 1) * bin_ns;
  for (std::int64_t edge = first_edge_ns; edge < top; edge *= 2) out.upper_ns.push_back(edge);
  out.upper_ns.push_back(top);
  out.counts.assign(out.upper_ns.size() + 1, 0);
  std::size_t coarse = 0;
  for (std::size_t b = 0; b + 1 < bins.size(); ++b) {
    const std::int64_t upper = (static_cast<std::int64_t>(b) + 1) * bin_ns;
    while (coarse < out.upper_ns.size() && upper > out.upper_ns[coarse]) ++coarse;
    out.counts[coarse] += bins[b];
  }
  out.counts.back() += bins.back();
  return out;
}

TimingSummary summarize(const TimingStats& stats) noexcept {
  TimingSummary s;
  s.period_ns = stats.period_ns;
  s.cycles = stats.cycles;
  s.overruns = stats.overruns;
  s.max_consecutive_overruns = stats.max_consecutive_overruns;
  s.wakeup = summarize(stats.wakeup);
  s.compute = summarize(stats.compute);
  return s;
}

}  // namespace knoblab::rt
