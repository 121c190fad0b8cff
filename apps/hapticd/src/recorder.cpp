#include "knoblab/hapticd/recorder.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "knoblab/hapticd/supervisor.hpp"

namespace knoblab::hapticd {

namespace {

// Held for a busy store when nobody says otherwise: a minute of the loop's
// output (at 10 kHz 600 000 samples, about 34 MB) outlasts any import.
constexpr double kDefaultBufferSeconds = 60.0;

// The largest commit when nobody says otherwise. A store that fell behind
// commits this much per fsync; copying it out under the lock takes well
// under a millisecond.
constexpr double kDefaultCommitSeconds = 2.0;

// Longest a pump() keeps writing before the store thread looks up.
constexpr auto kPumpBudget = std::chrono::milliseconds(50);

}  // namespace

Recorder::Recorder(store::Store* store, store::NewCapture defaults, RecorderOptions options)
    : store_(store), defaults_(std::move(defaults)), options_(std::move(options)) {
  set_max_buffered(options_.max_buffered);
  const double rate = defaults_.rate_hz > 0 ? defaults_.rate_hz : 10000.0;
  if (options_.max_commit_samples == 0)
    options_.max_commit_samples = static_cast<std::size_t>(rate * kDefaultCommitSeconds);
  writer_options_.batch_size = options_.max_commit_samples;
  writer_options_.on_commit = options_.on_commit;
  batch_.reserve(options_.max_commit_samples);
  // A short wait per attempt: a busy store costs the store thread a few
  // milliseconds, then it tries again on the next pump.
  if (store_) store_->set_busy_timeout(options_.busy_timeout_ms);
}

const char* to_string(RecordingKind k) {
  switch (k) {
    case RecordingKind::stimulus: return "stimulus";
    case RecordingKind::calibration: return "calibration";
    case RecordingKind::trial: return "trial";
    case RecordingKind::other: return "other";
  }
  return "?";
}

void Recorder::describe(std::uint32_t recording_id, const store::NewCapture& info, RecordingKind kind) {
  std::lock_guard lock(described_mutex_);
  described_[recording_id] = {info, kind};
}

void Recorder::set_max_buffered(std::size_t samples) {
  if (samples == 0) {
    const double rate = defaults_.rate_hz > 0 ? defaults_.rate_hz : 10000.0;
    samples = static_cast<std::size_t>(rate * kDefaultBufferSeconds);
  }
  std::lock_guard lock(mutex_);
  options_.max_buffered = samples;
  capacity_.store(samples, std::memory_order_relaxed);
}

void Recorder::start(const LoopRecord& r) {
  Recording rec;
  rec.id = r.recording_id;
  {
    std::lock_guard lock(described_mutex_);
    const auto it = described_.find(rec.id);
    rec.info = it != described_.end() ? it->second.info : defaults_;
    if (it != described_.end()) rec.kind = it->second.kind;
    // Ids only grow: anything described up to this one is used or never ran.
    described_.erase(described_.begin(), described_.upper_bound(rec.id));
  }
  rec.info.has_command = true;
  if (rec.info.source.empty()) rec.info.source = "hapticd";
  rec.first_seq = r.seq;
  const double rate = rec.info.rate_hz > 0 ? rec.info.rate_hz : defaults_.rate_hz > 0 ? defaults_.rate_hz : 10000.0;
  rec.dt = 1.0 / rate;
  recordings_.push_back(std::move(rec));
  std::lock_guard lock(bio_mutex_);
  bio_.clear();
  start_s_ = static_cast<double>(r.now_ns) * 1e-9;  // the recording's t = 0
  bio_seq_offset_ = 0;
  bio_last_seq_ = -1;
  bio_open_ = true;
}

void Recorder::end_back() {
  Recording& rec = recordings_.back();
  rec.ended = true;
  std::lock_guard lock(bio_mutex_);
  // The box's samples that arrived after the recording's last sample (the
  // writer learns of its end a little later) belong to no recording.
  for (const store::BiometricSample& b : bio_)
    if (b.t <= rec.last_t) rec.bio.push_back(b);
  bio_.clear();
  bio_open_ = false;
}

void Recorder::take(const LoopRecord& r) {
  std::lock_guard lock(mutex_);
  // A gap in the cycle numbers is records the ring dropped. They belong to
  // the recording on both sides of the gap; at a boundary they may belong to
  // either, so both are charged ("up to"). A gap between records of no
  // recording costs nobody anything.
  const std::uint64_t gap = r.seq > next_seq_ ? r.seq - next_seq_ : 0;
  next_seq_ = r.seq + 1;
  const std::uint32_t id = r.recording_id;
  if (id != current_) {
    if (current_ != 0) {
      if (gap) {
        recordings_.back().lost += gap;
        recordings_.back().lost_maybe = true;
      }
      end_back();
    }
    current_ = id;
    if (id == 0) return;
    start(r);
    if (gap) {
      recordings_.back().lost += gap;
      recordings_.back().lost_maybe = true;
    }
  } else if (id == 0) {
    return;
  } else if (gap) {
    recordings_.back().lost += gap;
  }

  Recording& rec = recordings_.back();
  if (!rec.cut.empty()) return;  // cut short: the rest of it is not stored
  if (store_ && queued_ >= options_.max_buffered) {
    (void)cut(rec, "store busy: its buffer of " + std::to_string(options_.max_buffered) + " samples filled",
        false);
    return;
  }
  rec.faults |= r.faults;
  // Cut short on request (stop_capture, or a mode change during a run): the
  // samples are good, but not the capture that was asked for.
  if (r.end == RecordingEnd::stopped) rec.stopped = true;
  ++rec.taken;
  // A trial that spans idle and render once lost its render samples: the
  // mode's own t went back to 0 and the store refused them as out of order.
  store::Sample sample = r.sample;
  sample.t = static_cast<double>(r.seq - rec.first_seq) * rec.dt;
  rec.last_t = sample.t;
  if (!store_) return;
  rec.samples.push_back(sample);
  ++queued_;
  const std::uint64_t buffered = buffered_.load(std::memory_order_relaxed) + 1;
  buffered_.store(buffered, std::memory_order_relaxed);
  if (buffered > max_buffered_.load(std::memory_order_relaxed))
    max_buffered_.store(buffered, std::memory_order_relaxed);
}

std::optional<std::string> Recorder::cut(Recording& rec, const std::string& why, bool discard) {
  if (rec.cut.empty()) {
    rec.cut = why;
    failed_.fetch_add(1, std::memory_order_relaxed);
    std::fprintf(stderr, "hapticd: recording %u cut short: %s\n", rec.id, why.c_str());
    // While the loop still records it, it must stop: the motor must not go
    // on being driven for samples nobody will see.
    if (!rec.ended) safe_needed_ = true;
  }
  if (!discard || rec.discard) return std::nullopt;
  rec.discard = true;
  queued_ -= rec.samples.size();
  rec.samples.clear();
  if (!rec.writer) return std::nullopt;
  return end_reason(rec);
}

std::string Recorder::end_reason(const Recording& rec) const {
  std::string why;
  const auto add = [&](const std::string& part) { why += (why.empty() ? "" : "; ") + part; };
  if (!rec.cut.empty()) add(rec.cut);
  if (rec.faults != 0) add("fault: " + fault_list(rec.faults));
  if (rec.stopped) add("stopped by request after " + std::to_string(rec.taken) + " samples");
  if (rec.lost != 0)
    add("ring dropped " + std::string(rec.lost_maybe ? "up to " : "") + std::to_string(rec.lost) +
        " samples");
  if (rec.unstorable != 0)
    add(std::to_string(rec.unstorable) + " samples not stored (" + rec.unstorable_why + ")");
  return why;
}

void Recorder::finalize_front() {
  Recording& rec = recordings_.front();
  FinishedRecording f;
  f.recording_id = rec.id;
  f.kind = rec.kind;
  if (rec.writer) {
    f.capture_id = rec.writer->capture_id();
    f.samples = rec.writer->committed();
  } else if (!store_) {
    f.samples = rec.taken;
  }
  f.end_reason = end_reason(rec);
  f.complete = f.end_reason.empty();
  queued_ -= rec.samples.size();
  finished_.push_back(std::move(f));
  recordings_.pop_front();
}

void Recorder::pump() {
  const auto until = std::chrono::steady_clock::now() + kPumpBudget;
  while (write_front(until)) {
  }
  std::lock_guard lock(mutex_);
  update_stats();
}

bool Recorder::write_front(std::chrono::steady_clock::time_point until) {
  // What to write, copied out under the lock. take() only ever appends to
  // the back of recordings_ and of their sample deques, and only this thread
  // removes from the front, so `rec` stays valid without the lock; its
  // writer is this thread's alone.
  Recording* rec = nullptr;
  bool ends = false;  // the batch holds the recording's last sample
  store::NewCapture info;
  {
    std::lock_guard lock(mutex_);
    if (recordings_.empty()) return false;
    rec = &recordings_.front();
    if (!store_ || rec->discard) {
      if (!rec->ended) return false;
      finalize_front();
      return true;
    }
    const std::size_t n = std::min(rec->samples.size(), options_.max_commit_samples);
    batch_.assign(rec->samples.begin(), rec->samples.begin() + static_cast<std::ptrdiff_t>(n));
    ends = rec->ended && n == rec->samples.size();
    if (!rec->writer) info = rec->info;
  }

  std::size_t written = 0;  // of batch_, taken by the writer (or refused as unstorable)
  std::uint64_t unstorable = 0;
  std::string unstorable_why;
  // Hands the written samples' places over to the writer, under the lock.
  const auto consume = [&] {
    std::lock_guard lock(mutex_);
    for (std::size_t i = 0; i < written; ++i) rec->samples.pop_front();
    queued_ -= written;
    if (unstorable != 0 && rec->unstorable == 0) rec->unstorable_why = unstorable_why;
    rec->unstorable += unstorable;
  };
  try {
    if (!rec->writer) rec->writer.emplace(store_->begin_capture(info, writer_options_));
    store::CaptureWriter& w = *rec->writer;
    try {
      for (const store::Sample& sample : batch_) {
        const std::int64_t before = w.appended();
        try {
          w.append(sample);
        } catch (const std::invalid_argument& e) {
          // A sample the store cannot hold (a non-finite value): it is left
          // out and the capture says so; the rest is still worth keeping.
          if (unstorable++ == 0) unstorable_why = e.what();
        } catch (const store::StoreError&) {
          // A full batch failed to commit: the writer keeps it (and this
          // sample, if it took it), and retries on the next append.
          if (w.appended() > before) ++written;
          throw;
        }
        ++written;
        if (w.appended() - w.committed() == 1) rec->uncommitted_t = sample.t;
      }
      // One commit per batch at most: a store that fell behind catches up
      // in large commits, one that keeps up commits every interval.
      const std::int64_t held = w.appended() - w.committed();
      if (held > 0 && !batch_.empty() && batch_.back().t - rec->uncommitted_t >= options_.commit_interval_s)
        w.flush();
    } catch (...) {
      consume();
      throw;
    }
    consume();
    if (!ends) return written == options_.max_commit_samples && std::chrono::steady_clock::now() < until;

    std::string why;
    std::vector<store::BiometricSample> bio;
    {
      std::lock_guard lock(mutex_);
      why = end_reason(*rec);
      if (!rec->bio_saved) bio = rec->bio;
    }
    if (!rec->bio_saved) {
      if (!bio.empty()) store_->append_biometrics(w.capture_id(), bio);
      rec->bio_saved = true;
    }
    if (why.empty())
      w.finish();
    else
      w.finish_incomplete(why);
    std::lock_guard lock(mutex_);
    finalize_front();
    return std::chrono::steady_clock::now() < until;
  } catch (const store::StoreError& e) {
    if (store::sqlite::is_busy(e)) {
      // Another writer holds the lock: keep everything, try again later.
      retries_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    std::optional<std::string> abandon;
    {
      std::lock_guard lock(mutex_);
      abandon = cut(*rec, std::string("store error: ") + e.what(), true);
    }
    if (abandon) {
      try {
        rec->writer->abandon(*abandon);
      } catch (const std::exception&) {
        // The store refuses even that; the row stays 'recording' until the
        // next open after hapticd exits marks it 'incomplete'.
      }
    }
    return true;
  }
}

void Recorder::update_stats() {
  std::uint64_t buffered = queued_;
  for (const Recording& rec : recordings_)
    if (rec.writer && !rec.discard)
      buffered += static_cast<std::uint64_t>(rec.writer->appended() - rec.writer->committed());
  buffered_.store(buffered, std::memory_order_relaxed);
  if (buffered > max_buffered_.load(std::memory_order_relaxed))
    max_buffered_.store(buffered, std::memory_order_relaxed);
}

void Recorder::close() {
  std::lock_guard lock(mutex_);
  if (current_ != 0) end_back();
  current_ = 0;
}

void Recorder::abandon_all(const std::string& reason) {
  // Only at shutdown, when nothing is taken any more: the store calls under
  // the lock hold up nobody.
  std::lock_guard lock(mutex_);
  if (current_ != 0) end_back();  // normally close() came first
  current_ = 0;
  while (!recordings_.empty()) {
    Recording& rec = recordings_.front();
    if (rec.cut.empty()) rec.cut = reason;
    rec.ended = true;
    if (rec.writer && !rec.discard) {
      try {
        rec.writer->abandon(end_reason(rec));
      } catch (const std::exception&) {
        // As in cut(): recovery marks it once hapticd is gone.
      }
    }
    finalize_front();
  }
  update_stats();
}

bool Recorder::idle() const {
  std::lock_guard lock(mutex_);
  return recordings_.empty();
}

bool Recorder::safe_state_needed() {
  std::lock_guard lock(mutex_);
  const bool needed = safe_needed_;
  safe_needed_ = false;
  return needed;
}

void Recorder::add_biometrics(const store::BiometricSample& b) {
  std::lock_guard lock(bio_mutex_);
  if (!bio_open_) return;
  store::BiometricSample s = b;
  s.t -= start_s_;
  // A counter that went back (a restarted box) would repeat a stored seq,
  // and the store refuses the whole batch: number on from the last one.
  if (s.seq + bio_seq_offset_ <= bio_last_seq_) bio_seq_offset_ = bio_last_seq_ + 1 - s.seq;
  s.seq += bio_seq_offset_;
  bio_last_seq_ = s.seq;
  bio_.push_back(s);
}

std::vector<FinishedRecording> Recorder::take_finished() {
  std::lock_guard lock(mutex_);
  std::vector<FinishedRecording> out;
  out.swap(finished_);
  return out;
}

RecorderStats Recorder::stats() const {
  RecorderStats s;
  s.buffered = buffered_.load(std::memory_order_relaxed);
  s.max_buffered = max_buffered_.load(std::memory_order_relaxed);
  s.capacity = capacity_.load(std::memory_order_relaxed);
  s.retries = retries_.load(std::memory_order_relaxed);
  s.failed = failed_.load(std::memory_order_relaxed);
  return s;
}

}  // namespace knoblab::hapticd
