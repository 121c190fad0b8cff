// Seqlock: readers never see a half-written snapshot while the writer runs.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <thread>

#include "knoblab/rt/seqlock.hpp"
#include "knoblab/rt/stats_publisher.hpp"

using namespace knoblab::rt;

namespace {
// 4 KiB: a torn copy would show different stamps in different words.
struct Stamped {
  std::uint64_t words[512] = {};
};
struct Odd {  // size not a multiple of 8
  char text[13] = "initial";
};
}  // namespace

TEST(Seqlock, ReadsTheInitialThenThePublishedValue) {
  Seqlock<Odd> lock;
  EXPECT_EQ(lock.version(), 0U);
  EXPECT_STREQ(lock.read().text, "initial");
  Odd v;
  std::snprintf(v.text, sizeof v.text, "%s", "published!");
  lock.publish(v);
  EXPECT_EQ(lock.version(), 1U);
  Odd out;
  ASSERT_TRUE(lock.try_read(out));
  EXPECT_STREQ(out.text, "published!");
}

TEST(Seqlock, ConcurrentReaderOnlySeesWholeSnapshots) {
  auto lock = std::make_unique<Seqlock<Stamped>>();
  std::atomic<bool> done{false};
  std::thread writer([&] {
    auto v = std::make_unique<Stamped>();
    for (std::uint64_t stamp = 1; !done.load(std::memory_order_relaxed); ++stamp) {
      for (auto& w : v->words) w = stamp;
      lock->publish(*v);
    }
  });
  auto snap = std::make_unique<Stamped>();
  std::uint64_t torn = 0, backwards = 0, last = 0, failed_attempts = 0;
  for (int i = 0; i < 200'000; ++i) {
    while (!lock->try_read(*snap)) ++failed_attempts;
    const std::uint64_t stamp = snap->words[0];
    for (std::uint64_t w : snap->words) torn += w != stamp;
    backwards += stamp < last;
    last = stamp;
  }
  done = true;
  writer.join();
  EXPECT_EQ(torn, 0U);
  EXPECT_EQ(backwards, 0U);
  EXPECT_GT(last, 0U) << "the writer never published";
  std::printf("[ figures  ] %llu publishes, %llu read attempts overlapped a write\n",
              static_cast<unsigned long long>(lock->version()),
              static_cast<unsigned long long>(failed_attempts));
}

TEST(StatsPublisher, SnapshotsOfLiveStatsAreInternallyConsistent) {
  auto publisher = std::make_unique<StatsPublisher>();
  std::atomic<bool> done{false};
  std::thread loop([&] {  // stands in for the realtime loop
    auto stats = std::make_unique<TimingStats>();
    for (std::int64_t i = 0; !done.load(std::memory_order_relaxed); ++i) {
      stats->wakeup.record((i * 7919) % 3'000'000);
      stats->compute.record((i * 104729) % 150'000);
      ++stats->cycles;
      publisher->publish(*stats);
    }
  });
  auto snap = std::make_unique<TimingStats>();
  std::uint64_t inconsistent = 0;
  for (int i = 0; i < 2'000; ++i) {
    *snap = publisher->read();
    std::uint64_t wake = 0, compute = 0;
    for (auto c : snap->wakeup.bins()) wake += c;
    for (auto c : snap->compute.bins()) compute += c;
    inconsistent += wake != snap->wakeup.count || compute != snap->compute.count ||
                    snap->cycles != snap->wakeup.count || snap->cycles != snap->compute.count;
  }
  done = true;
  loop.join();
  EXPECT_EQ(inconsistent, 0U);
  EXPECT_GT(publisher->read().cycles, 0U);
}
