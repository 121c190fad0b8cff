#include "knoblab/hapticd/recorder.hpp"

namespace knoblab::hapticd {

void Recorder::describe_next(const store::NewCapture& info) { next_ = info; }

void Recorder::open(std::uint32_t recording_id) {
  recording_id_ = recording_id;
  lost_samples_ = false;
  if (!store_) return;
  store::NewCapture info = next_.value_or(defaults_);
  next_.reset();
  info.has_command = true;
  if (info.source.empty()) info.source = "hapticd";
  writer_.emplace(store_->begin_capture(info));
  std::lock_guard lock(bio_mutex_);
  open_capture_ = writer_->capture_id();
  bio_.clear();
}

void Recorder::finish() {
  FinishedRecording f;
  f.recording_id = recording_id_;
  f.complete = !lost_samples_;
  if (writer_) {
    {
      std::lock_guard lock(bio_mutex_);
      // The writer closes a capture a little after its last sample; samples
      // of the box that arrived in between belong to no capture.
      std::erase_if(bio_, [&](const store::BiometricSample& b) { return b.t > last_t_; });
      if (!bio_.empty()) store_->append_biometrics(writer_->capture_id(), bio_);
      bio_.clear();
      open_capture_ = 0;
    }
    f.capture_id = writer_->capture_id();
    f.samples = writer_->appended();
    // Lost samples leave a hole: such a capture must not claim completeness.
    if (lost_samples_) writer_->abandon();
    else writer_->finish();
    writer_.reset();
  }
  finished_.push_back(f);
  recording_id_ = 0;
}

void Recorder::drop_open() {
  dropped_recording_ = recording_id_;
  FinishedRecording f;
  f.recording_id = recording_id_;
  f.complete = false;
  if (writer_) {
    f.capture_id = writer_->capture_id();
    f.samples = writer_->committed();
  }
  writer_.reset();  // its destructor tries to mark the capture 'incomplete'
  finished_.push_back(f);
  recording_id_ = 0;
  std::lock_guard lock(bio_mutex_);
  open_capture_ = 0;
  bio_.clear();
}

void Recorder::take(const LoopRecord& r, std::uint64_t dropped_before) {
  if (r.recording_id != 0 && r.recording_id == dropped_recording_) return;
  if (dropped_before > 0 && recording_id_ != 0) lost_samples_ = true;
  if (r.recording_id != recording_id_) {
    if (recording_id_ != 0) finish();
    if (r.recording_id != 0) {
      open(r.recording_id);
      std::lock_guard lock(bio_mutex_);
      start_s_ = static_cast<double>(r.now_ns) * 1e-9 - r.sample.t;
    }
  }
  if (recording_id_ != 0 && writer_) {
    writer_->append(r.sample);
    last_t_ = r.sample.t;
  }
}

void Recorder::close() {
  if (recording_id_ != 0) finish();
}

void Recorder::add_biometrics(const store::BiometricSample& b) {
  std::lock_guard lock(bio_mutex_);
  if (open_capture_ == 0) return;
  store::BiometricSample s = b;
  s.t -= start_s_;
  bio_.push_back(s);
}

std::vector<FinishedRecording> Recorder::take_finished() {
  std::vector<FinishedRecording> out;
  out.swap(finished_);
  return out;
}

}  // namespace knoblab::hapticd
