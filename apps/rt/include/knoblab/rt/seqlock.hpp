// One writer publishes copies of a value; any number of readers take
// consistent copies. The writer never waits (it is the realtime loop); a
// reader that overlaps a write notices and retries.
//
// The value is stored as relaxed atomic 64-bit words and bracketed by a
// sequence counter with fences (Boehm, "Can seqlocks get along with
// programming language memory models?", 2012), so there is no data race
// even while a reader copies during a write.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <thread>
#include <type_traits>

namespace knoblab::rt {

template <class T>
class Seqlock {
  static_assert(std::is_trivially_copyable_v<T>, "snapshots are copied bytewise");
  static_assert(std::is_default_constructible_v<T>);

 public:
  explicit Seqlock(const T& initial = T{}) noexcept { store_words(initial); }
  Seqlock(const Seqlock&) = delete;
  Seqlock& operator=(const Seqlock&) = delete;

  // Writer only (one writer). Wait-free: a fixed number of stores.
  void publish(const T& value) noexcept {
    const std::uint64_t seq = seq_.load(std::memory_order_relaxed);
    seq_.store(seq + 1, std::memory_order_relaxed);  // odd: write in progress
    std::atomic_thread_fence(std::memory_order_release);
    store_words(value);
    seq_.store(seq + 2, std::memory_order_release);
  }

  // One attempt; false when a write overlapped the copy (out is then garbage).
  bool try_read(T& out) const noexcept {
    const std::uint64_t before = seq_.load(std::memory_order_acquire);
    if (before & 1U) return false;
    auto* bytes = reinterpret_cast<unsigned char*>(&out);
    for (std::size_t i = 0; i < kWords; ++i) {
      const std::uint64_t w = words_[i].load(std::memory_order_relaxed);
      const std::size_t offset = i * sizeof w;
      const std::size_t n = sizeof(T) - offset < sizeof w ? sizeof(T) - offset : sizeof w;
      std::memcpy(bytes + offset, &w, n);
    }
    std::atomic_thread_fence(std::memory_order_acquire);
    return seq_.load(std::memory_order_relaxed) == before;
  }

  // Retries until a consistent copy is taken. For non-realtime readers.
  T read() const noexcept {
    T out;
    while (!try_read(out)) std::this_thread::yield();
    return out;
  }

  // Completed publishes so far (0 before the first).
  std::uint64_t version() const noexcept { return seq_.load(std::memory_order_acquire) / 2; }

 private:
  static constexpr std::size_t kWords = (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);

  void store_words(const T& value) noexcept {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t i = 0; i < kWords; ++i) {
      std::uint64_t w = 0;
      const std::size_t offset = i * sizeof w;
      const std::size_t n = sizeof(T) - offset < sizeof w ? sizeof(T) - offset : sizeof w;
      std::memcpy(&w, bytes + offset, n);
      words_[i].store(w, std::memory_order_relaxed);
    }
  }

  alignas(64) std::atomic<std::uint64_t> seq_{0};
  alignas(64) std::atomic<std::uint64_t> words_[kWords];
};

}  // namespace knoblab::rt
