// Latest<T>: hands the newest value from one non-realtime writer to the
// realtime loop without locks or allocation (a triple buffer). The loop never
// waits; the writer never waits; a value written twice before the loop looks
// is simply replaced. Used for parameter updates such as slider drags.
#pragma once

#include <atomic>
#include <cstdint>
#include <type_traits>

namespace knoblab::hapticd {

template <class T>
class Latest {
  static_assert(std::is_trivially_copyable_v<T>, "Latest<T> copies T in the realtime loop");

 public:
  explicit Latest(const T& initial = T{}) {
    for (auto& s : slots_) s = initial;
  }

  // Writer side (one non-realtime thread).
  void publish(const T& value) {
    slots_[back_] = value;
    // Swap our back slot with the middle one and mark it fresh.
    const std::uint8_t old = middle_.exchange(static_cast<std::uint8_t>(back_ | kFresh),
                                              std::memory_order_acq_rel);
    back_ = old & kIndex;
  }

  // Reader side (the realtime loop): true and a new value if one arrived.
  bool take(T& out) {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const std::uint8_t old = middle_.exchange(front_, std::memory_order_acq_rel);
    front_ = old & kIndex;
    out = slots_[front_];
    return true;
  }

 private:
  static constexpr std::uint8_t kIndex = 0x3, kFresh = 0x4;
  T slots_[3];
  std::uint8_t back_ = 0;              // writer's slot
  std::atomic<std::uint8_t> middle_{1};  // exchanged slot (+ fresh bit)
  std::uint8_t front_ = 2;             // reader's slot
};

}  // namespace knoblab::hapticd
