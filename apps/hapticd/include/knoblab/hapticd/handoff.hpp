// Handoff<T>: gives the realtime loop a new immutable object (built, with
// allocations, by non-realtime code) and hands the old one back for deletion
// — the loop never allocates or frees. One publisher thread, one loop.
// A loop that cross-fades takes with take_keeping_previous(): the object it
// replaces stays alive (previous()) until the loop lets go of it with
// release_previous(); no further offer is taken meanwhile.
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
    delete_if_owned(retired_more_.load());
    delete previous_;
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
  void reclaim() {
    delete_if_owned(retired_.exchange(nullptr, std::memory_order_acq_rel));
    delete_if_owned(retired_more_.exchange(nullptr, std::memory_order_acq_rel));
  }

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

  // Realtime: takes an offer, if there is one and no previous object is
  // still held; true when it did. The replaced object becomes previous().
  bool take_keeping_previous() {
    T* offer = pending_.load(std::memory_order_acquire);
    if (!offer || has_previous_) return false;
    previous_ = current_;
    has_previous_ = true;
    current_ = offer == &kNone ? nullptr : offer;
    pending_.store(nullptr, std::memory_order_release);
    return true;
  }
  // Realtime: the objects held, without taking anything.
  const T* held() const { return current_; }
  const T* previous() const { return previous_; }
  bool has_previous() const { return has_previous_; }
  // Realtime: the previous object goes back to the publisher for deletion
  // (false: no room yet; try again next cycle). A release comes after the
  // offer that replaced the object, so no publish (which reclaims) need
  // follow it before the next take: two slots hold what two releases
  // between publishes let go of — the release before a take and the one
  // after it.
  bool release_previous() {
    if (!has_previous_) return true;
    if (previous_) {
      std::atomic<T*>* slot = retired_.load(std::memory_order_acquire) == nullptr ? &retired_
                              : retired_more_.load(std::memory_order_acquire) == nullptr ? &retired_more_
                                                                                         : nullptr;
      if (!slot) return false;
      slot->store(previous_, std::memory_order_release);
    }
    previous_ = nullptr;
    has_previous_ = false;
    return true;
  }

 private:
  static void delete_if_owned(T* p) {
    if (p != &kNone) delete p;
  }
  inline static T kNone{};  // "clear" marker, never deleted
  std::atomic<T*> pending_{nullptr};
  std::atomic<T*> retired_{nullptr};
  std::atomic<T*> retired_more_{nullptr};  // take_keeping_previous's second slot
  T* current_ = nullptr;  // loop-owned
  T* previous_ = nullptr;  // loop-owned while has_previous_
  bool has_previous_ = false;
};

}  // namespace knoblab::hapticd
