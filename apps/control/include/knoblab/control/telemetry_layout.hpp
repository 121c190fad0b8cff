// The telemetry ring as it lies in POSIX shared memory (layout version 1,
// documented in docs/protocol.md for readers in other languages):
//
//   [TelemetryHeader, padded to 64 bytes * n][slot 0][slot 1]…[slot capacity−1]
//
// One producer (the daemon's realtime loop) and any number of readers that
// never write. Record n lives in slot n mod capacity. Each slot is a
// seqlock: its sequence is 2n+1 while record n is written and 2n+2 once it
// is complete, so a reader that sees the same even value 2n+2 before and
// after copying has an untorn record n. `head` counts complete records.
#pragma once

#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "knoblab/control/telemetry_sample.hpp"

namespace knoblab::control::telemetry {

// Atomics in shared memory must not hide a lock inside the process.
static_assert(std::atomic<std::uint64_t>::is_always_lock_free);
static_assert(std::atomic<std::uint32_t>::is_always_lock_free);

inline constexpr std::uint64_t kMagic = 0x314D4C54424F4E4BULL;  // "KNOBTLM1" little-endian
inline constexpr std::uint32_t kLayoutVersion = 1;
inline constexpr std::size_t kRecordWords = sizeof(TelemetryRecord) / sizeof(std::uint64_t);

struct Header {
  std::atomic<std::uint64_t> magic;  // stored last by the creator (release)
  std::uint32_t layout_version;
  std::uint32_t record_size;         // sizeof(TelemetryRecord)
  std::uint32_t slot_size;           // sizeof(Slot)
  std::uint32_t decimation;          // loop cycles per record
  std::uint64_t capacity;            // slots; a power of two
  double loop_rate_hz;               // records arrive at loop_rate_hz / decimation
  std::atomic<std::uint32_t> writer_closed;  // 1 once the daemon shut the ring down
  std::uint32_t reserved;
  alignas(64) std::atomic<std::uint64_t> head;  // records published so far
};

struct Slot {
  std::atomic<std::uint64_t> seq;
  // The record as words, each accessed atomically (relaxed), so a concurrent
  // read is a stale value rather than a data race; seq says whether to keep it.
  std::atomic<std::uint64_t> words[kRecordWords];
};

// The byte offsets docs/protocol.md promises to readers in other languages.
static_assert(std::is_standard_layout_v<Header> && std::is_standard_layout_v<Slot>);
static_assert(offsetof(Header, layout_version) == 8 && offsetof(Header, record_size) == 12 &&
              offsetof(Header, slot_size) == 16 && offsetof(Header, decimation) == 20 &&
              offsetof(Header, capacity) == 24 && offsetof(Header, loop_rate_hz) == 32 &&
              offsetof(Header, writer_closed) == 40 && offsetof(Header, head) == 64 && sizeof(Header) == 128);
static_assert(offsetof(Slot, words) == 8 && sizeof(Slot) == 72);

inline constexpr std::size_t kSlotsOffset = (sizeof(Header) + 63) / 64 * 64;
inline constexpr std::size_t region_size(std::uint64_t capacity) {
  return kSlotsOffset + static_cast<std::size_t>(capacity) * sizeof(Slot);
}

inline void store_record(Slot& slot, const TelemetryRecord& r) noexcept {
  const double doubles[] = {r.t, r.theta, r.omega, r.torque, r.torque_min, r.torque_max, r.command};
  for (std::size_t i = 0; i < 7; ++i) slot.words[i].store(std::bit_cast<std::uint64_t>(doubles[i]), std::memory_order_relaxed);
  slot.words[7].store(std::uint64_t{r.mode} | (std::uint64_t{r.fault_bits} << 32), std::memory_order_relaxed);
}

inline TelemetryRecord load_record(const Slot& slot) noexcept {
  std::uint64_t w[kRecordWords];
  for (std::size_t i = 0; i < kRecordWords; ++i) w[i] = slot.words[i].load(std::memory_order_relaxed);
  TelemetryRecord r;
  r.t = std::bit_cast<double>(w[0]);
  r.theta = std::bit_cast<double>(w[1]);
  r.omega = std::bit_cast<double>(w[2]);
  r.torque = std::bit_cast<double>(w[3]);
  r.torque_min = std::bit_cast<double>(w[4]);
  r.torque_max = std::bit_cast<double>(w[5]);
  r.command = std::bit_cast<double>(w[6]);
  r.mode = static_cast<std::uint32_t>(w[7] & 0xFFFFFFFFu);
  r.fault_bits = static_cast<std::uint32_t>(w[7] >> 32);
  return r;
}

}  // namespace knoblab::control::telemetry
