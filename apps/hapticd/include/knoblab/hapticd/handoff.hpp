// Handoff<T>: gives the realtime loop a new immutable object (built, with
// allocations, by non-realtime code) and hands the old one back for deletion
// — the loop never allocates or frees. One publisher thread, one loop.
#pragma once

#include <atomic>
#include <memory>

namespace knoblab::hapticd {

template <class T>
class Handoff {
 public:
  Handoff() = default;
  Handoff(const Handoff&) = delete;
  Handoff& operator=(const Handoff&) = delete;
  ~Handoff() {
    delete_if_owned(pending_.load());
    delete_if_owned(retired_.load());
    delete current_;
  }

  // Non-realtime: offer `next` (nullptr = nothing). False while the loop has
  // not yet taken the previous offer; `next` is then left with the caller,
  // to offer again a cycle later.
  bool publish(std::unique_ptr<T>&& next) {
    reclaim();
    T* expected = nullptr;
    T* raw = next ? next.get() : &kNone;
    if (!pending_.compare_exchange_strong(expected, raw, std::memory_order_acq_rel)) return false;
    next.release();
    return true;
  }
  // Non-realtime: frees what the loop has let go of.
  void reclaim() { delete_if_owned(retired_.exchange(nullptr, std::memory_order_acq_rel)); }

  // Realtime: the current object (nullptr if none), taking a new one if offered.
  const T* current() {
    T* offer = pending_.load(std::memory_order_acquire);
    if (offer && retired_.load(std::memory_order_acquire) == nullptr) {
      retired_.store(current_, std::memory_order_release);
      current_ = offer == &kNone ? nullptr : offer;
      pending_.store(nullptr, std::memory_order_release);
    }
    return current_;
  }

 private:
  static void delete_if_owned(T* p) {
    if (p != &kNone) delete p;
  }
  inline static T kNone{};  // "clear" marker, never deleted
  std::atomic<T*> pending_{nullptr};
  std::atomic<T*> retired_{nullptr};
  T* current_ = nullptr;  // loop-owned
};

}  // namespace knoblab::hapticd
