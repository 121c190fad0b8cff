// Histogram binning, quantiles from known inputs, summaries and JSON.
#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "knoblab/rt/stats_json.hpp"
#include "knoblab/rt/timing_stats.hpp"

using namespace knoblab::rt;

TEST(Histogram, BinsValuesAndKeepsExactExtremes) {
  Histogram<1000, 10> h;  // 1 µs bins up to 10 µs
  for (std::int64_t ns : {0, 999, 1000, 9999, 10000, 50000, -5}) h.record(ns);
  EXPECT_EQ(h.count, 7U);
  EXPECT_EQ(h.counts[0], 3U);  // 0, 999 and the negative value
  EXPECT_EQ(h.counts[1], 1U);  // 1000
  EXPECT_EQ(h.counts[9], 1U);  // 9999
  EXPECT_EQ(h.overflow(), 2U);  // 10000 and 50000
  EXPECT_EQ(h.min_ns, -5);
  EXPECT_EQ(h.max_ns, 50000);
  EXPECT_EQ(h.sum_ns, 0 + 999 + 1000 + 9999 + 10000 + 50000 - 5);
}

TEST(Histogram, QuantilesAreBinUpperEdgesFromKnownInputs) {
  auto h = std::make_unique<WakeupHistogram>();
  // 1000 samples, one in the middle of each 1 µs bin 0..999.
  for (std::int64_t i = 0; i < 1000; ++i) h->record(i * 1000 + 500);
  // rank ceil(q·1000): median is sample 500 (499.5 µs, bin 499), …
  EXPECT_EQ(quantile_ns(*h, 0.5), 500'000);
  EXPECT_EQ(quantile_ns(*h, 0.99), 990'000);
  EXPECT_EQ(quantile_ns(*h, 0.999), 999'000);
  EXPECT_EQ(quantile_ns(*h, 1.0), 999'500);  // the exact max
  EXPECT_EQ(quantile_ns(*h, 0.0), 500);      // the exact min
  const HistogramSummary s = summarize(*h);
  EXPECT_EQ(s.count, 1000U);
  EXPECT_EQ(s.median_ns, 500'000);
  EXPECT_EQ(s.p99_ns, 990'000);
  EXPECT_EQ(s.p999_ns, 999'000);
  EXPECT_EQ(s.max_ns, 999'500);
  EXPECT_DOUBLE_EQ(s.mean_ns, 500'000.0);  // mean of i·1000 + 500 for i < 1000
}

TEST(Histogram, QuantileIsCappedAtTheExactMax) {
  ComputeHistogram h;  // 50 ns bins
  for (int i = 0; i < 100; ++i) h.record(1234);
  EXPECT_EQ(quantile_ns(h, 0.5), 1234);  // bin [1200, 1250) capped at max 1234
  EXPECT_EQ(quantile_ns(h, 0.99), 1234);
}

TEST(Histogram, QuantileInTheOverflowBinIsTheMax) {
  auto h = std::make_unique<WakeupHistogram>();
  for (int i = 0; i < 998; ++i) h->record(10'000);  // 10 µs
  h->record(5'000'000);  // 5 ms: beyond the 2 ms range
  h->record(7'000'000);
  EXPECT_EQ(h->overflow(), 2U);
  EXPECT_EQ(quantile_ns(*h, 0.5), 11'000);
  EXPECT_EQ(quantile_ns(*h, 0.99), 11'000);
  EXPECT_EQ(quantile_ns(*h, 0.999), 7'000'000);
  EXPECT_EQ(summarize(*h).overflow, 2U);
}

TEST(Histogram, EmptyHistogramSummarisesToZeros) {
  ComputeHistogram h;
  EXPECT_EQ(quantile_ns(h, 0.5), 0);
  const HistogramSummary s = summarize(h);
  EXPECT_EQ(s.count, 0U);
  EXPECT_EQ(s.min_ns, 0);
  EXPECT_EQ(s.max_ns, 0);
}

TEST(Histogram, DoublingBinsSumFineBinsUnderEachDoublingEdgeAndKeepTheOverflowLast) {
  Histogram<1000, 10> h;  // 1 µs bins up to 10 µs: coarse edges 1, 2, 4, 8, 10 µs
  for (std::int64_t ns : {500, 1500, 2500, 3500, 7000, 8500, 9999, 12000, 40000}) h.record(ns);
  const DoublingBins d = doubling_bins(h.bins(), 1000, 1000);
  EXPECT_EQ(d.upper_ns, (std::vector<std::int64_t>{1000, 2000, 4000, 8000, 10000}));
  // [0,1) | [1,2) | [2,4) | [4,8) | [8,10) | ≥ 10 µs
  EXPECT_EQ(d.counts, (std::vector<std::uint64_t>{1, 1, 2, 1, 2, 2}));
  std::uint64_t total = 0;
  for (const auto c : d.counts) total += c;
  EXPECT_EQ(total, h.count);
}

TEST(TimingStats, JsonCarriesTheSummary) {
  auto stats = std::make_unique<TimingStats>();
  stats->period_ns = 100'000;
  stats->cycles = 4;
  stats->overruns = 1;
  stats->max_consecutive_overruns = 1;
  for (std::int64_t ns : {2'000, 3'000, 4'000, 60'000}) stats->wakeup.record(ns);
  for (std::int64_t ns : {100, 200, 300, 400}) stats->compute.record(ns);

  const auto j = nlohmann::json::parse(to_json(*stats));
  EXPECT_EQ(j["period_ns"], 100'000);
  EXPECT_EQ(j["cycles"], 4);
  EXPECT_EQ(j["overruns"], 1);
  EXPECT_EQ(j["wakeup_latency"]["count"], 4);
  EXPECT_EQ(j["wakeup_latency"]["min_ns"], 2'000);
  EXPECT_EQ(j["wakeup_latency"]["max_ns"], 60'000);
  EXPECT_EQ(j["wakeup_latency"]["median_ns"], 4'000);  // rank 2: 3 µs sample, bin upper edge
  EXPECT_DOUBLE_EQ(j["wakeup_latency"]["mean_ns"].get<double>(), 17'250.0);
  EXPECT_EQ(j["compute_time"]["p99_ns"], 400);
  EXPECT_FALSE(j["wakeup_latency"].contains("bins"));

  const auto jb = nlohmann::json::parse(to_json(*stats, /*with_bins=*/true));
  const auto& bins = jb["wakeup_latency"]["bins"];
  EXPECT_EQ(bins["bin_ns"], 1000);
  ASSERT_EQ(bins["counts"].size(), 4U);
  EXPECT_EQ(bins["counts"][0], nlohmann::json::parse("[2000,1]"));
  EXPECT_EQ(bins["counts"][3], nlohmann::json::parse("[60000,1]"));
  EXPECT_EQ(bins["overflow"], 0);
}

TEST(TimingStats, JsonOfAnEmptyHistogramUsesNull) {
  auto stats = std::make_unique<TimingStats>();
  stats->compute.record(500);
  const auto j = nlohmann::json::parse(to_json(summarize(*stats)));
  EXPECT_EQ(j["wakeup_latency"]["count"], 0);
  EXPECT_TRUE(j["wakeup_latency"]["median_ns"].is_null());
  EXPECT_EQ(j["compute_time"]["max_ns"], 500);
}
