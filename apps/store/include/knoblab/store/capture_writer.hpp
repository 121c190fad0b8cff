// Streams samples of one capture into the store in committed batches.
//
// Each full batch is inserted and committed in one transaction (with
// synchronous=FULL, so it survives a crash or power loss once commit
// returns); a crash loses at most the batch being filled. The capture row's
// sample_count is updated in the same transaction, so it always equals the
// committed sample rows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "knoblab/store/sqlite.hpp"
#include "knoblab/store/types.hpp"

namespace knoblab::store {

struct WriterOptions {
  std::size_t batch_size = 2000;
  // Called after each commit with the total committed so far (progress
  // display; the crash test uses it to learn what must have survived).
  std::function<void(std::int64_t committed)> on_commit;
};

class CaptureWriter {
 public:
  CaptureWriter(CaptureWriter&& other) noexcept;
  CaptureWriter& operator=(CaptureWriter&&) = delete;
  CaptureWriter(const CaptureWriter&) = delete;
  CaptureWriter& operator=(const CaptureWriter&) = delete;
  // Not finished: abandon() - flushes what it can and marks the capture
  // 'incomplete'.
  ~CaptureWriter();

  std::int64_t capture_id() const { return id_; }

  // Buffers one sample; commits the batch when full. Throws
  // std::invalid_argument (sample dropped, writer still usable) for a
  // non-finite value or a t not after the previous one, StoreError when a
  // commit fails: nothing buffered is lost, the next append() or flush()
  // retries (appended() tells whether this sample was taken).
  void append(const Sample& sample);
  void flush();   // commit whatever is buffered now
  void finish();  // flush, mark 'complete'
  // Flush, mark 'incomplete' with this end_reason (not empty; e.g. "fault:
  // estop"). Like finish(), a StoreError (e.g. the database is busy) loses
  // nothing and leaves the writer open: call it again later.
  void finish_incomplete(std::string_view reason);
  // Best effort, for when the capture cannot go on: flush, mark 'incomplete'
  // with `reason`; if the batch cannot be saved, mark it without the batch.
  void abandon(std::string_view reason = "abandoned by its writer");
  // For a run cancelled before its end: removes the capture with what is
  // committed of it, and the knob begin_capture made for it when no other
  // capture uses it, in one transaction, so nothing of it stays. A
  // StoreError leaves the writer open (abandon() still marks it).
  void discard();

  std::int64_t committed() const { return committed_; }
  std::int64_t appended() const { return committed_ + static_cast<std::int64_t>(batch_.size()); }

 private:
  friend class Store;
  CaptureWriter(std::shared_ptr<sqlite::Connection> db, std::int64_t id, bool has_command,
                WriterOptions options, std::optional<std::int64_t> created_knob);
  void insert_batch();
  void committed_batch();
  void close(const char* status, std::string_view reason);

  std::shared_ptr<sqlite::Connection> db_;  // the Store's connection
  std::int64_t id_;
  bool has_command_;
  WriterOptions options_;
  sqlite::Statement insert_;
  sqlite::Statement update_count_;
  std::vector<Sample> batch_;
  std::int64_t committed_ = 0;
  double last_t_ = 0;
  bool closed_ = false;
  std::optional<std::int64_t> created_knob_;  // made by begin_capture for this capture
};

}  // namespace knoblab::store
