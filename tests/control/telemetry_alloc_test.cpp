// TelemetryWriter::push runs in the 10 kHz loop: it must never allocate.
// This file replaces the global operator new for the whole test binary and
// counts allocations made while `counting` is set on this thread.
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

#include "knoblab/control/telemetry_writer.hpp"
#include "telemetry_support.hpp"

namespace {
std::atomic<std::size_t> allocations{0};
thread_local bool counting = false;
}  // namespace

// GCC sees malloc behind operator new after inlining and would flag free()
// in the matching delete; the pairing is right by construction here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  if (counting) ++allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace knoblab::control::test {
namespace {

TEST(TelemetryRealtime, PushNeverAllocates) {
  TelemetryConfig cfg;
  cfg.shm_name = unique_shm_name("alloc");
  cfg.capacity = 1024;
  TelemetryWriter w(cfg);
  counting = true;
  void* volatile probe = ::operator new(64);  // proves the counter works (volatile: not elided)
  ::operator delete(probe);
  const std::size_t baseline = allocations.exchange(0);
  for (std::uint64_t i = 0; i < 200'000; ++i) w.push(counter_sample(i));
  counting = false;
  EXPECT_EQ(baseline, 1u);
  EXPECT_EQ(allocations.load(), 0u);
  EXPECT_EQ(w.records_published(), 20'000u);
}

}  // namespace
}  // namespace knoblab::control::test
