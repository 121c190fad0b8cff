// Counts every global operator new while g_counting is up: for tests of code
// that runs in the realtime loop and must never allocate. It replaces the
// global operator new and delete, so include it in exactly one file of a test
// binary.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace knoblab::test {
inline std::atomic<bool> g_counting{false};
inline std::atomic<long> g_allocations{0};

inline void* counted(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
}  // namespace knoblab::test

void* operator new(std::size_t n) { return knoblab::test::counted(n); }
void* operator new[](std::size_t n) { return knoblab::test::counted(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (knoblab::test::g_counting.load(std::memory_order_relaxed)) knoblab::test::g_allocations.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
