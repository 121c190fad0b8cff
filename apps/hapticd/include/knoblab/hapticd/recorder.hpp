// The non-realtime end of the loop's ring: every record of a recording goes
// into the store in committed batches. Nothing here is ever called by the
// loop.
//
// Two threads use it. The ring thread takes records (take): that only
// buffers, under a lock no store call is ever made under, so the ring keeps
// draining and telemetry keeps flowing however long a commit takes (an
// fsync on an SD card or an emulated disk takes seconds). The store thread
// writes (pump): it copies what is waiting, writes it without the lock, and
// commits once per batch, so a store that fell behind catches up in a few
// large commits instead of many small ones. A store call waits for another
// writer's lock at most a few milliseconds; while the store stays busy (an
// import, another process) the samples wait in memory and the next pump
// retries. The buffer is bounded; a recording that outgrows it, or meets a
// store error that is not "busy", cannot be stored: it is cut there, marked
// 'incomplete' with the reason, and safe_state_needed() asks the daemon to
// stop it and make the motor safe.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "knoblab/hapticd/core.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::hapticd {

// What made a recording. Every kind is stored the same way, as a capture;
// the kind says which command started it (docs/architecture.md, "Names").
enum class RecordingKind : std::uint8_t { stimulus, calibration, trial, other };
const char* to_string(RecordingKind k);

struct FinishedRecording {
  std::uint32_t recording_id = 0;
  RecordingKind kind = RecordingKind::other;
  std::int64_t capture_id = 0;  // 0 when nothing was stored
  std::int64_t samples = 0;     // committed to the store (taken, without a store)
  bool complete = true;         // false: see end_reason
  // Why it is incomplete, as stored in captures.end_reason: "fault: estop",
  // "ring dropped 12 samples", "store busy", "store error: …"; joined by
  // "; " when several. Empty when complete.
  std::string end_reason;
};

// How much the recorder holds in memory for a busy store, and how hard it
// has had to try. Read from any thread.
struct RecorderStats {
  std::uint64_t buffered = 0;      // samples taken from the ring, not yet committed
  std::uint64_t max_buffered = 0;  // the most buffered at any time
  std::uint64_t capacity = 0;      // buffered beyond this cuts the recording
  std::uint64_t retries = 0;       // store attempts that found the database busy
  std::uint64_t failed = 0;        // recordings cut because they could not be stored
};

struct RecorderOptions {
  // Samples held for a busy store; 0: 60 s at the defaults' rate_hz.
  std::size_t max_buffered = 0;
  // Each store attempt waits this long for another writer's lock, then the
  // store thread retries on the next pump.
  int busy_timeout_ms = 10;
  // Samples are committed at least this often (in the recording's time), not
  // only in full batches: a power cut loses at most this much of a capture,
  // at 250 Hz as at 10 kHz, besides what the store had not yet been given.
  double commit_interval_s = 0.25;
  // The most one commit holds; 0: 2 s at the defaults' rate_hz. A store that
  // fell behind catches up in commits this large.
  std::size_t max_commit_samples = 0;
  // Called on the store thread after each commit with what the capture has
  // committed so far (a slow disk in tests holds the commit here).
  std::function<void(std::int64_t committed)> on_commit;
};

class Recorder {
 public:
  // `defaults` describes recordings nobody described (e.g. a trial). With a
  // store, sets that connection's busy timeout (options.busy_timeout_ms).
  // The store is used by pump()'s thread only.
  Recorder(store::Store* store, store::NewCapture defaults, RecorderOptions options = {});

  // How recording `recording_id` is described in the store (set before the
  // loop starts it; any thread). A description whose recording never starts
  // (the loop refused it) is forgotten once a later recording starts.
  void describe(std::uint32_t recording_id, const store::NewCapture& info,
                RecordingKind kind = RecordingKind::other);

  // --- the ring thread ---
  // One record from the ring, in order of LoopRecord::seq: a gap in seq is
  // records the ring lost, charged to the recording they belonged to.
  // Buffers only; never waits for the store, never throws for it.
  void take(const LoopRecord& record);
  // The loop stopped: the open recording ends with its last record.
  void close();

  // --- the store thread ---
  // Writes what was taken, as far as the store lets it now, for at most
  // about 50 ms (so the thread can notice a shutdown).
  void pump();
  // Gives up on everything still buffered (the store stayed busy at shutdown):
  // marks what it can 'incomplete' with `reason`.
  void abandon_all(const std::string& reason);

  // --- any thread ---
  // Nothing taken is left to write (after close(): everything is stored).
  bool idle() const;

  // True once per recording that could not be stored: the caller stops it
  // and puts the motor in the safe state (kFaultRecording).
  bool safe_state_needed();

  // Biometrics arrive from the Modbus thread, `t` in CLOCK_MONOTONIC
  // seconds: kept for the open recording, rebased onto its clock.
  void add_biometrics(const store::BiometricSample& b);

  // Recordings that ended and were stored since the last call.
  std::vector<FinishedRecording> take_finished();

  RecorderStats stats() const;

 private:
  // One recording on its way into the store; the front of recordings_ is the
  // one being written, the back the one the loop may still be recording.
  // Its fields are under mutex_, except those marked "store thread".
  struct Recording {
    std::uint32_t id = 0;
    store::NewCapture info;
    RecordingKind kind = RecordingKind::other;
    std::optional<store::CaptureWriter> writer;  // store thread: once its row exists
    std::deque<store::Sample> samples;           // taken, not yet handed to the writer
    std::int64_t taken = 0;
    std::uint32_t faults = 0;     // every Fault bit latched during it
    bool stopped = false;         // its last record says it was stopped by request
    std::uint64_t lost = 0;       // records the ring dropped (seq gaps) that were, or may have been, its
    bool lost_maybe = false;      // some of `lost` may have belonged to a neighbour
    std::uint64_t unstorable = 0; // samples the writer refused (non-finite values)
    std::string unstorable_why;
    std::string cut;              // why it was cut short ("store busy", "store error: …")
    bool discard = false;         // a store error: nothing more of it is written
    bool ended = false;           // its last record has been taken
    std::vector<store::BiometricSample> bio;
    bool bio_saved = false;       // store thread
    double last_t = 0.0;          // t of its newest sample
    // Its clock: t = (cycle − first_seq) · dt, whatever modes it spans
    // (render starts its own clock when entered, idle counts from start).
    std::uint64_t first_seq = 0;
    double dt = 0.0;
    double uncommitted_t = 0.0;   // store thread: t of the oldest sample the writer holds uncommitted
  };

  // options_.max_buffered, 0 meaning the default.
  void set_max_buffered(std::size_t samples);
  // All under mutex_.
  void start(const LoopRecord& r);
  void end_back();
  // Marks `rec` cut short; with `discard`, drops what it holds and returns
  // the reason its writer must be abandoned with (outside the lock).
  std::optional<std::string> cut(Recording& rec, const std::string& why, bool discard);
  void finalize_front();
  std::string end_reason(const Recording& rec) const;
  void update_stats();

  // Store thread: writes one batch of the front recording, finishes it when
  // it has ended and everything is written. False: nothing more to do now.
  bool write_front(std::chrono::steady_clock::time_point until);

  store::Store* store_;
  store::NewCapture defaults_;
  RecorderOptions options_;
  store::WriterOptions writer_options_;
  std::vector<store::Sample> batch_;  // store thread: copied out of the front recording

  // The recordings, everything take() does and the finished list.
  mutable std::mutex mutex_;
  std::mutex described_mutex_;  // describe() comes from control threads
  struct Description {
    store::NewCapture info;
    RecordingKind kind = RecordingKind::other;
  };
  std::map<std::uint32_t, Description> described_;
  std::deque<Recording> recordings_;
  std::uint32_t current_ = 0;      // recording_id of the newest record taken
  std::uint64_t next_seq_ = 0;     // seq the next record should have
  std::size_t queued_ = 0;         // samples in all recordings' deques
  bool safe_needed_ = false;
  std::vector<FinishedRecording> finished_;

  mutable std::mutex bio_mutex_;
  bool bio_open_ = false;          // a recording is open: biometrics are kept
  std::vector<store::BiometricSample> bio_;
  double start_s_ = 0.0;           // CLOCK_MONOTONIC of the open recording's t = 0
  // The box's counter restarts with the box (or wraps): its samples keep
  // their order in the recording through an offset added from then on.
  std::int64_t bio_seq_offset_ = 0, bio_last_seq_ = -1;

  std::atomic<std::uint64_t> buffered_{0}, max_buffered_{0}, capacity_{0}, retries_{0}, failed_{0};
};

}  // namespace knoblab::hapticd
