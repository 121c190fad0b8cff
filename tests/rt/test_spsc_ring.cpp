// SpscRing: single-thread semantics, then two threads and another process.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <new>
#include <thread>
#include <vector>

#include "knoblab/rt/spsc_ring.hpp"

using knoblab::rt::SpscRing;

namespace {
struct Item {
  std::uint64_t seq;
  double value;
};
}  // namespace

static_assert(std::is_standard_layout_v<SpscRing<Item, 8>>);
static_assert(SpscRing<Item, 8>::capacity() == 8);

TEST(SpscRing, EmptyRingPopsNothing) {
  SpscRing<int, 4> ring;
  int out = -1;
  EXPECT_FALSE(ring.try_pop(out));
  EXPECT_EQ(out, -1);
  EXPECT_EQ(ring.size_approx(), 0U);
  std::array<int, 3> buf{};
  EXPECT_EQ(ring.pop_bulk(buf), 0U);
}

TEST(SpscRing, PopsInPushOrder) {
  SpscRing<Item, 8> ring;
  for (std::uint64_t i = 0; i < 5; ++i) ASSERT_TRUE(ring.try_push({i, 0.5 * double(i)}));
  EXPECT_EQ(ring.size_approx(), 5U);
  for (std::uint64_t i = 0; i < 5; ++i) {
    Item it{};
    ASSERT_TRUE(ring.try_pop(it));
    EXPECT_EQ(it.seq, i);
    EXPECT_DOUBLE_EQ(it.value, 0.5 * double(i));
  }
  Item it{};
  EXPECT_FALSE(ring.try_pop(it));
}

TEST(SpscRing, FullRingRefusesAndCountsDrops) {
  SpscRing<int, 8> ring;
  for (int i = 0; i < 8; ++i) ASSERT_TRUE(ring.try_push(i));
  EXPECT_EQ(ring.size_approx(), 8U);
  EXPECT_FALSE(ring.try_push(100));
  EXPECT_FALSE(ring.try_push(101));
  EXPECT_EQ(ring.dropped(), 2U);
  int out = -1;
  ASSERT_TRUE(ring.try_pop(out));
  EXPECT_EQ(out, 0);  // the refused items did not overwrite anything
  EXPECT_TRUE(ring.try_push(8));
  EXPECT_EQ(ring.dropped(), 2U);
  for (int i = 1; i <= 8; ++i) {
    ASSERT_TRUE(ring.try_pop(out));
    EXPECT_EQ(out, i);
  }
}

TEST(SpscRing, WrapsAroundManyTimes) {
  SpscRing<std::uint64_t, 4> ring;
  std::uint64_t next_in = 0, next_out = 0;
  // Varying fill levels so head and tail cross the end of the array at every offset.
  for (int round = 0; round < 1000; ++round) {
    const int n = 1 + round % 4;
    for (int i = 0; i < n; ++i) ASSERT_TRUE(ring.try_push(next_in++));
    const int m = 1 + (round * 7) % n;
    for (int i = 0; i < m; ++i) {
      std::uint64_t v = 0;
      ASSERT_TRUE(ring.try_pop(v));
      ASSERT_EQ(v, next_out++);
    }
    std::uint64_t v = 0;
    while (ring.try_pop(v)) ASSERT_EQ(v, next_out++);
  }
  EXPECT_EQ(next_in, next_out);
  EXPECT_EQ(ring.dropped(), 0U);
}

TEST(SpscRing, PopBulkTakesWhatFitsAcrossTheWrap) {
  SpscRing<int, 8> ring;
  for (int i = 0; i < 6; ++i) ASSERT_TRUE(ring.try_push(i));
  std::array<int, 4> four{};
  ASSERT_EQ(ring.pop_bulk(four), 4U);
  EXPECT_EQ(four, (std::array<int, 4>{0, 1, 2, 3}));
  for (int i = 6; i < 12; ++i) ASSERT_TRUE(ring.try_push(i));  // now wraps: slots 4..7, 0..3
  std::array<int, 16> many{};
  ASSERT_EQ(ring.pop_bulk(many), 8U);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(many[std::size_t(i)], 4 + i);
  EXPECT_EQ(ring.pop_bulk(many), 0U);
}

TEST(SpscRing, TwoThreadStressKeepsOrderWithoutLossOrDuplication) {
  constexpr std::uint64_t kItems = 20'000'000;
  auto ring = std::make_unique<SpscRing<std::uint64_t, 1024>>();
  std::uint64_t full_retries = 0;
  const auto t0 = std::chrono::steady_clock::now();
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kItems; ++i)
      while (!ring->try_push(i)) ++full_retries;  // each refusal is a counted drop
  });
  std::uint64_t expected = 0, mismatches = 0;
  std::array<std::uint64_t, 64> buf{};
  while (expected < kItems) {
    // Alternate the two ways of consuming.
    if (expected % 2 == 0) {
      const std::size_t n = ring->pop_bulk(buf);
      for (std::size_t i = 0; i < n; ++i) mismatches += buf[i] != expected++;
    } else {
      std::uint64_t v = 0;
      if (ring->try_pop(v)) mismatches += v != expected++;
    }
  }
  producer.join();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::uint64_t extra = 0;
  EXPECT_FALSE(ring->try_pop(extra)) << "an item beyond the last one: " << extra;
  EXPECT_EQ(mismatches, 0U);
  EXPECT_EQ(expected, kItems);
  EXPECT_EQ(ring->dropped(), full_retries);
  std::printf("[ figures  ] %llu items in %.2f s (%.1f M/s), %llu pushes refused while full\n",
              static_cast<unsigned long long>(kItems), s, double(kItems) / s / 1e6,
              static_cast<unsigned long long>(full_retries));
}

TEST(SpscRing, WorksAcrossProcessesInSharedMemory) {
  using Ring = SpscRing<Item, 256>;
  constexpr std::uint64_t kItems = 1'000'000;
  void* mem = mmap(nullptr, sizeof(Ring), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(mem, MAP_FAILED);
  auto* ring = new (mem) Ring;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // producer process: only async-signal-safe-ish work, then _exit
    for (std::uint64_t i = 0; i < kItems; ++i)
      while (!ring->try_push({i, double(i)})) {
      }
    _exit(0);
  }
  std::uint64_t expected = 0, mismatches = 0;
  while (expected < kItems) {
    Item it{};
    if (ring->try_pop(it)) {
      mismatches += it.seq != expected || it.value != double(expected);
      ++expected;
    }
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(mismatches, 0U);
  ring->~Ring();
  munmap(mem, sizeof(Ring));
}
