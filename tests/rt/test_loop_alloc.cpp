// The realtime contract: once cycles run, nothing on the loop thread calls
// operator new. This file replaces the global operator new for the whole
// test binary; it counts only on threads that raised t_counting, and the
// cycle raises it on its first call, so the loop machinery between and after
// cycles is watched until the loop thread exits.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>

#include "knoblab/rt/periodic_loop.hpp"

namespace {
thread_local bool t_counting = false;
std::atomic<long> g_allocations{0};

void* counted(std::size_t n) {
  if (t_counting) g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return counted(n); }
void* operator new[](std::size_t n) { return counted(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (t_counting) g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace knoblab::rt;

namespace {
LoopConfig small(bool free_run, std::int64_t cycles) {
  LoopConfig c;
  c.rate_hz = 5000;
  c.free_run = free_run;
  c.max_cycles = cycles;
  c.publish_every = 7;
  return c;
}
}  // namespace

TEST(LoopAllocation, CounterSeesAllocationsOnTheLoopThread) {
  std::atomic<bool> stop{false};
  g_allocations = 0;
  run(small(false, 10), [](const CycleInfo& info) {
    t_counting = true;
    if (info.index == 5) {
      auto p = std::make_unique<int>(3);  // what a careless cycle might do
      (void)p;
    }
  }, stop);
  EXPECT_EQ(g_allocations.load(), 1);
}

TEST(LoopAllocation, PacedLoopDoesNotAllocate) {
  auto publisher = std::make_unique<StatsPublisher>();
  std::atomic<bool> stop{false};
  g_allocations = 0;
  const LoopResult r = run(small(false, 300), [](const CycleInfo&) { t_counting = true; }, stop,
                           publisher.get());
  EXPECT_EQ(r.stats.cycles, 300U);
  EXPECT_EQ(g_allocations.load(), 0);
}

TEST(LoopAllocation, FreeRunLoopDoesNotAllocate) {
  auto publisher = std::make_unique<StatsPublisher>();
  std::atomic<bool> stop{false};
  g_allocations = 0;
  const LoopResult r = run(small(true, 20'000), [](const CycleInfo&) { t_counting = true; }, stop,
                           publisher.get());
  EXPECT_EQ(r.stats.cycles, 20'000U);
  EXPECT_EQ(g_allocations.load(), 0);
}

TEST(LoopAllocation, StoppingOnTheFlagDoesNotAllocate) {
  std::atomic<bool> stop{false};
  g_allocations = 0;
  run(small(false, -1), [&](const CycleInfo& info) {
    t_counting = true;
    if (info.index == 50) stop = true;
    return true;
  }, stop);
  EXPECT_EQ(g_allocations.load(), 0);
}
