// The non-realtime end of the loop's ring: every record of a recording goes
// into the store in committed batches; a few per second go to telemetry.
// Runs on the writer thread; nothing here is ever called by the loop.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "knoblab/hapticd/core.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::hapticd {

struct FinishedRecording {
  std::uint32_t recording_id = 0;
  std::int64_t capture_id = 0;
  std::int64_t samples = 0;
  bool complete = true;  // false when the ring dropped samples of it
};

class Recorder {
 public:
  // `defaults` describes recordings nobody described (e.g. a trial).
  Recorder(store::Store* store, store::NewCapture defaults) : store_(store), defaults_(std::move(defaults)) {}

  // How the next recording is described in the store (set before starting it).
  void describe_next(const store::NewCapture& info);

  // One record from the ring, in order. `dropped_before` = records the ring
  // lost since the previous call (they make the open capture incomplete).
  void take(const LoopRecord& record, std::uint64_t dropped_before);
  // The loop stopped: close whatever is open.
  void close();
  // The store failed: forget the open capture (it stays 'incomplete') and
  // ignore the rest of that recording.
  void drop_open();

  // Biometrics arrive from the Modbus thread, `t` in CLOCK_MONOTONIC
  // seconds: kept for the open capture, rebased onto its clock.
  void add_biometrics(const store::BiometricSample& b);

  // Recordings that ended since the last call.
  std::vector<FinishedRecording> take_finished();

 private:
  void open(std::uint32_t recording_id);
  void finish();

  store::Store* store_;
  store::NewCapture defaults_;
  std::optional<store::NewCapture> next_;
  std::optional<store::CaptureWriter> writer_;
  std::uint32_t recording_id_ = 0;
  bool lost_samples_ = false;
  std::uint32_t dropped_recording_ = 0;  // after drop_open(): its records are ignored
  std::vector<FinishedRecording> finished_;
  mutable std::mutex bio_mutex_;
  std::vector<store::BiometricSample> bio_;
  std::int64_t open_capture_ = 0;
  double start_s_ = 0.0;
  double last_t_ = 0.0;   // t of the open capture's newest sample  // CLOCK_MONOTONIC of the open capture's first sample
};

}  // namespace knoblab::hapticd
