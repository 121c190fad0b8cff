#include "knoblab/store/capture_writer.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "internal.hpp"

namespace knoblab::store {

CaptureWriter::CaptureWriter(std::shared_ptr<sqlite::Connection> db, std::int64_t id,
                             bool has_command, WriterOptions options,
                             std::optional<std::int64_t> created_knob)
    : db_(std::move(db)),
      id_(id),
      has_command_(has_command),
      options_(std::move(options)),
      insert_(db_->prepare(
          "INSERT INTO samples (capture_id, idx, t, theta, omega, alpha, torque, command, flags)"
          " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)")),
      update_count_(db_->prepare("UPDATE captures SET sample_count = ?2 WHERE id = ?1")),
      created_knob_(created_knob) {
  batch_.reserve(options_.batch_size);  // no allocation while capturing
  insert_.bind_int(1, id_);             // bindings survive the auto-reset after each row
  update_count_.bind_int(1, id_);
}

CaptureWriter::CaptureWriter(CaptureWriter&& o) noexcept
    : db_(std::move(o.db_)),
      id_(o.id_),
      has_command_(o.has_command_),
      options_(std::move(o.options_)),
      insert_(std::move(o.insert_)),
      update_count_(std::move(o.update_count_)),
      batch_(std::move(o.batch_)),
      committed_(o.committed_),
      last_t_(o.last_t_),
      closed_(o.closed_),
      created_knob_(o.created_knob_) {
  o.closed_ = true;
}

CaptureWriter::~CaptureWriter() {
  if (closed_ || !db_) return;
  try {
    abandon();
  } catch (...) {
    // Nothing to report to from a destructor; the next Store::open of a
    // dead process's capture will still mark it 'incomplete'.
  }
}

void CaptureWriter::append(const Sample& s) {
  if (closed_) throw std::logic_error("append to a finished capture");
  const bool finite = std::isfinite(s.t) && std::isfinite(s.theta) && std::isfinite(s.omega) &&
                      std::isfinite(s.alpha) && std::isfinite(s.torque) &&
                      (!has_command_ || std::isfinite(s.command));
  if (!finite)
    throw std::invalid_argument("sample " + std::to_string(appended()) + " has a non-finite value");
  if (appended() > 0 && !(s.t > last_t_))
    throw std::invalid_argument("sample " + std::to_string(appended()) +
                                ": t does not increase");
  // A previous commit failed and the batch is still full: retry it first.
  if (batch_.size() >= options_.batch_size) flush();
  batch_.push_back(s);
  last_t_ = s.t;
  if (batch_.size() >= options_.batch_size) flush();
}

// Inserts the buffered samples; the caller holds the transaction.
void CaptureWriter::insert_batch() {
  std::int64_t idx = committed_;
  for (const Sample& s : batch_) {
    insert_.bind_int(2, idx++)
        .bind_double(3, s.t)
        .bind_double(4, s.theta)
        .bind_double(5, s.omega)
        .bind_double(6, s.alpha)
        .bind_double(7, s.torque);
    if (has_command_)
      insert_.bind_double(8, s.command);
    else
      insert_.bind_null(8);
    insert_.bind_int(9, s.flags);
    insert_.run();
  }
}

void CaptureWriter::committed_batch() {
  const bool any = !batch_.empty();
  committed_ += static_cast<std::int64_t>(batch_.size());
  batch_.clear();
  if (any && options_.on_commit) options_.on_commit(committed_);
}

void CaptureWriter::flush() {
  if (closed_ || batch_.empty()) return;
  sqlite::Transaction tx(*db_);
  insert_batch();
  update_count_.bind_int(2, committed_ + static_cast<std::int64_t>(batch_.size())).run();
  tx.commit();
  committed_batch();
}

// Last batch and final status in one transaction: no crash window in which
// all samples are there but the capture still says 'recording'.
void CaptureWriter::close(const char* status, std::string_view reason) {
  sqlite::Transaction tx(*db_);
  insert_batch();
  auto st = db_->prepare(
      "UPDATE captures SET status = ?2, sample_count = ?3, end_reason = ?4,"
      " finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ?1");
  st.bind_int(1, id_).bind_text(2, status).bind_int(
      3, committed_ + static_cast<std::int64_t>(batch_.size()));
  if (reason.empty())
    st.bind_null(4);
  else
    st.bind_text(4, reason);
  st.run();
  tx.commit();
  committed_batch();
  closed_ = true;
}

void CaptureWriter::finish() {
  if (closed_) throw std::logic_error("capture already finished");
  close("complete", {});
}

void CaptureWriter::finish_incomplete(std::string_view reason) {
  if (closed_) throw std::logic_error("capture already finished");
  if (reason.empty()) throw std::invalid_argument("an incomplete capture needs a reason");
  close("incomplete", reason);
}

void CaptureWriter::discard() {
  if (closed_) throw std::logic_error("capture already finished");
  detail::remove_unfinished_capture(*db_, id_, created_knob_);
  batch_.clear();
  closed_ = true;
}

void CaptureWriter::abandon(std::string_view reason) {
  if (closed_) return;
  if (reason.empty()) reason = "abandoned by its writer";
  try {
    close("incomplete", reason);
  } catch (const StoreError&) {
    batch_.clear();  // the batch cannot be saved; keep what is committed
    close("incomplete", reason);
  }
}

}  // namespace knoblab::store
