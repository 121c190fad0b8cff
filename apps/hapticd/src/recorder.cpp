#include "knoblab/hapticd/recorder.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "knoblab/hapticd/supervisor.hpp"

namespace knoblab::hapticd {

namespace {

// Held for a busy store when nobody says otherwise: a minute of the loop's
// output (at 10 kHz 600 000 samples, about 34 MB) outlasts any import.
constexpr double kDefaultBufferSeconds = 60.0;

// Longest a pump() keeps writing before the writer thread returns to the ring.
constexpr auto kPumpBudget = std::chrono::milliseconds(50);

}  // namespace

Recorder::Recorder(store::Store* store, store::NewCapture defaults, RecorderOptions options)
    : store_(store), defaults_(std::move(defaults)), options_(options) {
  set_max_buffered(options_.max_buffered);
  // A short wait per attempt: a busy store costs the writer thread a few
  // milliseconds, then it goes back to draining the ring and tries again.
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
  recordings_.push_back(std::move(rec));
  std::lock_guard lock(bio_mutex_);
  bio_.clear();
  start_s_ = static_cast<double>(r.now_ns) * 1e-9 - r.sample.t;
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
    cut(rec, "store busy: its buffer of " + std::to_string(options_.max_buffered) + " samples filled",
        false);
    return;
  }
  rec.faults |= r.faults;
  // Cut short on request (stop_capture, or a mode change during a run): the
  // samples are good, but not the capture that was asked for.
  if (r.end == RecordingEnd::stopped) rec.stopped = true;
  ++rec.taken;
  rec.last_t = r.sample.t;
  if (!store_) return;
  rec.samples.push_back(r.sample);
  ++queued_;
  const std::uint64_t buffered = buffered_.load(std::memory_order_relaxed) + 1;
  buffered_.store(buffered, std::memory_order_relaxed);
  if (buffered > max_buffered_.load(std::memory_order_relaxed))
    max_buffered_.store(buffered, std::memory_order_relaxed);
}

void Recorder::cut(Recording& rec, const std::string& why, bool discard) {
  if (rec.cut.empty()) {
    rec.cut = why;
    failed_.fetch_add(1, std::memory_order_relaxed);
    std::fprintf(stderr, "hapticd: recording %u cut short: %s\n", rec.id, why.c_str());
    // While the loop still records it, it must stop: the motor must not go
    // on being driven for samples nobody will see.
    if (!rec.ended) safe_needed_ = true;
  }
  if (!discard || rec.discard) return;
  rec.discard = true;
  queued_ -= rec.samples.size();
  rec.samples.clear();
  if (rec.writer) {
    try {
      rec.writer->abandon(end_reason(rec));
    } catch (const std::exception&) {
      // The store refuses even that; the row stays 'recording' until the
      // next open after hapticd exits marks it 'incomplete'.
    }
  }
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
  while (!recordings_.empty()) {
    Recording& rec = recordings_.front();
    if (!store_ || rec.discard) {
      if (!rec.ended) break;
      finalize_front();
      continue;
    }
    try {
      if (!rec.writer) rec.writer.emplace(store_->begin_capture(rec.info));
      std::size_t n = 0;
      while (!rec.samples.empty()) {
        const std::int64_t before = rec.writer->appended();
        const double t = rec.samples.front().t;
        try {
          rec.writer->append(rec.samples.front());
        } catch (const std::invalid_argument& e) {
          // A sample the store cannot hold (a non-finite value): it is left
          // out and the capture says so; the rest is still worth keeping.
          if (rec.unstorable++ == 0) rec.unstorable_why = e.what();
        } catch (const store::StoreError&) {
          // A full batch failed to commit: the writer keeps it (and this
          // sample, if it took it), and retries on the next append.
          if (rec.writer->appended() > before) {
            rec.samples.pop_front();
            --queued_;
          }
          throw;
        }
        rec.samples.pop_front();
        --queued_;
        const std::int64_t held = rec.writer->appended() - rec.writer->committed();
        if (held == 1) rec.uncommitted_t = t;
        if (held > 0 && t - rec.uncommitted_t >= options_.commit_interval_s) rec.writer->flush();
        if (++n % 256 == 0 && std::chrono::steady_clock::now() > until) {
          update_stats();
          return;
        }
      }
      if (!rec.ended) break;
      if (!rec.bio_saved) {
        if (!rec.bio.empty()) store_->append_biometrics(rec.writer->capture_id(), rec.bio);
        rec.bio_saved = true;
      }
      const std::string why = end_reason(rec);
      if (why.empty())
        rec.writer->finish();
      else
        rec.writer->finish_incomplete(why);
      finalize_front();
    } catch (const store::StoreError& e) {
      if (store::sqlite::is_busy(e)) {
        // Another writer holds the lock: keep everything, try again later.
        retries_.fetch_add(1, std::memory_order_relaxed);
        break;
      }
      cut(rec, std::string("store error: ") + e.what(), true);
    }
  }
  update_stats();
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
  if (current_ != 0) end_back();
  current_ = 0;
}

void Recorder::abandon_all(const std::string& reason) {
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

bool Recorder::safe_state_needed() {
  const bool needed = safe_needed_;
  safe_needed_ = false;
  return needed;
}

void Recorder::add_biometrics(const store::BiometricSample& b) {
  std::lock_guard lock(bio_mutex_);
  if (!bio_open_) return;
  store::BiometricSample s = b;
  s.t -= start_s_;
  bio_.push_back(s);
}

std::vector<FinishedRecording> Recorder::take_finished() {
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
