// A disk that takes as long as the test likes to commit (an SD card's or an
// emulated disk's fsync can take seconds): the recorder's on_commit hook
// holds the store thread inside its first commit, and every later one,
// until release().
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>

#include "knoblab/hapticd/recorder.hpp"

namespace knoblab::hapticd::testing {

class HeldCommit {
 public:
  HeldCommit() : released_(release_.get_future().share()) {}
  // Options whose commits wait here; this object must outlive their use.
  RecorderOptions options() {
    RecorderOptions o;
    o.on_commit = [this](std::int64_t) {
      if (first_.exchange(false)) entered_.set_value();
      released_.wait();
    };
    return o;
  }
  // True once the store thread is inside a commit (false after `timeout`).
  bool wait_entered(std::chrono::seconds timeout) {
    return entered_.get_future().wait_for(timeout) == std::future_status::ready;
  }
  void release() { release_.set_value(); }

 private:
  std::promise<void> release_;
  std::shared_future<void> released_;
  std::promise<void> entered_;
  std::atomic<bool> first_{true};
};

}  // namespace knoblab::hapticd::testing
