// Lock-free single-producer / single-consumer ring: the RT loop pushes
// samples, a non-RT thread drains them. Wait-free on both sides.
//
// All storage is inside the object (no heap, no pointers) and the class is
// standard-layout with lock-free (hence address-free) atomics, so it may also
// be placed in shared memory and used across processes: construct it once
// with placement new in the mapping, then one process produces, one consumes.
// A ring of large capacity is big: give it static storage, a heap object made
// before the loop starts, or shared memory, not the loop thread's stack.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

namespace knoblab::rt {

// One cache line on x86-64 and the usual ARM cores; keeps the producer's
// and the consumer's hot indices from false sharing.
inline constexpr std::size_t kCacheLineBytes = 64;

template <class T, std::size_t Capacity>
class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "ring slots are copied bytewise");
  static_assert(std::is_standard_layout_v<T>, "the ring must stay standard-layout");
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0,
                "Capacity must be a power of two");
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free,
                "needs lock-free 64-bit atomics (also for shared memory)");

 public:
  static constexpr std::size_t capacity() noexcept { return Capacity; }

  // Producer only. False (and one more drop counted) when the ring is full.
  bool try_push(const T& value) noexcept {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail - cached_head_ == Capacity) {
      cached_head_ = head_.load(std::memory_order_acquire);
      if (tail - cached_head_ == Capacity) {
        // Single writer: a plain load+store avoids a locked RMW in the loop.
        dropped_.store(dropped_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
        return false;
      }
    }
    slots_[tail & kMask] = value;
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Consumer only. False when the ring is empty.
  bool try_pop(T& out) noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (head == cached_tail_) {
      cached_tail_ = tail_.load(std::memory_order_acquire);
      if (head == cached_tail_) return false;
    }
    out = slots_[head & kMask];
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer only. Pops up to out.size() items in order; returns how many.
  std::size_t pop_bulk(std::span<T> out) noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    cached_tail_ = tail_.load(std::memory_order_acquire);
    const std::uint64_t available = cached_tail_ - head;
    const std::size_t n = available < out.size() ? static_cast<std::size_t>(available) : out.size();
    for (std::size_t i = 0; i < n; ++i) out[i] = slots_[(head + i) & kMask];
    head_.store(head + n, std::memory_order_release);
    return n;
  }

  // Items in the ring at some instant during the call; exact only when
  // neither side is running.
  std::size_t size_approx() const noexcept {
    // head first: tail only grows, so tail >= head holds for these two loads.
    const std::uint64_t head = head_.load(std::memory_order_acquire);
    const std::uint64_t tail = tail_.load(std::memory_order_acquire);
    const std::uint64_t n = tail - head;
    return n > Capacity ? Capacity : static_cast<std::size_t>(n);
  }

  bool empty_approx() const noexcept { return size_approx() == 0; }

  // Pushes refused because the ring was full, since construction.
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::uint64_t kMask = Capacity - 1;

  // Indices count up forever (2^64 pushes is centuries at 10 kHz); the slot
  // is index & kMask, and tail - head is the fill level.
  // Consumer's line: what it publishes, and its private copy of tail.
  alignas(kCacheLineBytes) std::atomic<std::uint64_t> head_{0};
  std::uint64_t cached_tail_ = 0;
  // Producer's line: what it publishes, its copy of head, its drop count.
  alignas(kCacheLineBytes) std::atomic<std::uint64_t> tail_{0};
  std::uint64_t cached_head_ = 0;
  std::atomic<std::uint64_t> dropped_{0};
  // Zeroed at construction: no indeterminate reads, and the pages get touched
  // before the loop starts rather than during it.
  alignas(kCacheLineBytes) T slots_[Capacity] = {};
};

}  // namespace knoblab::rt
