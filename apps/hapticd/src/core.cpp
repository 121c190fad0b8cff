#include "knoblab/hapticd/core.hpp"

#include <cmath>

namespace knoblab::hapticd {

const char* to_string(RecordingEnd e) {
  switch (e) {
    case RecordingEnd::none: return "none";
    case RecordingEnd::finished: return "finished";
    case RecordingEnd::stopped: return "stopped";
    case RecordingEnd::fault: return "fault";
  }
  return "?";
}

const char* to_string(Mode m) {
  switch (m) {
    case Mode::Idle: return "idle";
    case Mode::Render: return "render";
    case Mode::Capture: return "capture";
    case Mode::Calibrate: return "calibrate";
  }
  return "?";
}

namespace {
RenderConfig render_config(const CoreConfig& c) {
  RenderConfig r = c.render;
  r.rate_hz = c.rate_hz;
  r.torque_per_volt = c.limits.torque_per_volt;
  return r;
}

capture::SensorConfig sensor_config(const CoreConfig& c) {
  capture::SensorConfig s;
  s.rate_hz = c.rate_hz;
  s.calibration = c.calibration;
  return s;
}
}  // namespace

HapticCore::HapticCore(const CoreConfig& cfg)
    : cfg_(cfg), sensors_(sensor_config(cfg)), render_(render_config(cfg)), supervisor_(cfg.limits) {
  sensor_calibration_.publish(cfg.calibration);
}

CoreState HapticCore::state() const {
  const std::uint64_t p = published_.load(std::memory_order_acquire);
  CoreState s;
  s.mode = static_cast<Mode>(p & 0xff);
  s.faults = static_cast<std::uint32_t>((p >> 8) & 0xffffff);
  s.recording_id = static_cast<std::uint32_t>(p >> 32);
  s.cycles = published_cycles_.load(std::memory_order_relaxed);
  s.button_presses = published_presses_.load(std::memory_order_relaxed);
  return s;
}

void HapticCore::apply(const CoreCommand& c) {
  const bool faulted = supervisor_.latched() != 0;
  switch (c.kind) {
    case CoreCommand::SetMode: {
      // capture and calibration start only with their own commands
      if (c.mode == Mode::Capture || c.mode == Mode::Calibrate) break;
      if (c.mode == Mode::Render && faulted) break;  // nothing resumes while faulted
      if (running()) {  // the run ends on this cycle's record
        stop_pending_ = true;
        mode_after_stop_ = c.mode;
        break;
      }
      if (c.mode == Mode::Render && mode_ != Mode::Render) render_.reset();
      mode_ = c.mode;
      break;
    }
    case CoreCommand::SetRender:
      render_.set_params(c.render, c.immediate);
      break;
    case CoreCommand::StartCapture:
      if (running() || faulted || recording_ != 0) break;  // one recording at a time
      capture_ = c.capture;
      capture_left_ = c.capture_cycles;
      if (capture_left_ <= 0) break;
      begin_recording(c.recording_id);
      mode_ = Mode::Capture;
      break;
    case CoreCommand::StopCapture:
      if (running()) {
        stop_pending_ = true;
        mode_after_stop_ = Mode::Idle;
      }
      break;
    case CoreCommand::StartCalibration:
      if (running() || faulted || recording_ != 0) break;
      calibration_ = c.calibration;
      calibration_left_ = calibration_.cycles();
      if (calibration_left_ <= 0) break;  // an empty controller: nothing to run
      begin_recording(c.recording_id);     // recorded like a capture
      mode_ = Mode::Calibrate;
      break;
    case CoreCommand::StartRecording:
      if (recording_ == 0 && !faulted) begin_recording(c.recording_id);
      break;
    case CoreCommand::StopRecording:
      if (!running() && recording_ != 0) stop_recording_pending_ = true;
      break;
    case CoreCommand::ClearFault:
      clear_requested_ = true;
      forced_ = 0;
      break;
    case CoreCommand::ForceSafe:
      forced_ |= c.faults;
      break;
    case CoreCommand::SetSensorCalibration:
      if (running() || recording_ != 0) break;
      sensors_.set_calibration(c.sensors);
      sensor_calibration_.publish(c.sensors);
      break;
  }
}

void HapticCore::begin_recording(std::uint32_t id) { recording_ = id != 0 ? id : next_recording_++; }

void HapticCore::end_recording(RecordingEnd why, LoopRecord& rec) {
  if (mode_ == Mode::Calibrate) calibration_result_.publish(calibration_.data());
  if (recording_ != 0) rec.end = why;
  recording_ = 0;
  if (running()) mode_ = Mode::Idle;
  stop_pending_ = false;
  stop_recording_pending_ = false;
}

void HapticCore::measure_idle(const capture::SensorReading& in, capture::Sample& s) {
  s.t = static_cast<double>(cycles_) / cfg_.rate_hz;
  s.theta = in.theta;
  s.omega = in.omega;
  s.alpha = in.alpha;
  s.torque = in.torque;
}

void HapticCore::cycle(const capture::DaqInputs& in, const CycleContext& ctx, capture::DaqOutputs& out,
                       LoopRecord& rec) {
  // pop_slot_ is built once: a CoreCommand holds controllers whose default
  // construction designs filters (allocates), which the loop must not do.
  for (int i = 0; i < 4 && commands_.try_pop(pop_slot_); ++i) apply(pop_slot_);
  // After the commands: a ClearFault queued earlier cannot undo a request.
  forced_ |= safe_requests_.exchange(0, std::memory_order_acquire);
  render_.take_tiles();

  const capture::SensorReading& sensed = sensors_.update(in);
  capture::Sample& s = rec.sample;
  s = {};
  rec.now_ns = 0;
  rec.end = RecordingEnd::none;
  out = {};
  bool run_done = false;
  switch (mode_) {
    case Mode::Idle:
      measure_idle(sensed, s);
      break;
    case Mode::Render:
      render_.update(sensed, out, s);
      break;
    case Mode::Capture:
      capture_.update(sensed, out, s);
      run_done = --capture_left_ <= 0;
      break;
    case Mode::Calibrate:
      calibration_.update(sensed, out, s);
      run_done = --calibration_left_ <= 0;
      break;
  }

  io_errors_in_a_row_ = ctx.io_ok ? 0 : io_errors_in_a_row_ + 1;
  SafetyInputs safety;
  safety.estop = ctx.lines.estop;
  safety.external_faults = ctx.external_faults | forced_;
  // The limit watches the analysis filter in every mode: the quickest to
  // see a runaway, and the same whatever the mode records.
  safety.omega = sensed.omega;
  safety.sensors_finite = std::isfinite(sensed.theta) && std::isfinite(sensed.alpha) &&
                          std::isfinite(sensed.torque) && std::isfinite(s.omega) &&
                          std::isfinite(s.alpha) && std::isfinite(s.torque);
  safety.consecutive_overruns = static_cast<int>(ctx.consecutive_overruns);
  safety.consecutive_io_errors = io_errors_in_a_row_;
  safety.tracking_lost = mode_ == Mode::Capture && capture_.tracking_lost();
  safety.clear_requested = clear_requested_;
  clear_requested_ = false;
  const bool limited = supervisor_.apply(safety, out);
  s.command = out.motor_command_V;

  s.flags = (out.amp_enable ? interchange::kAmpEnabled : 0u) | (ctx.lines.estop ? interchange::kEstopActive : 0u) |
            (supervisor_.safe_state() ? interchange::kFaultLatched : 0u) |
            (limited ? interchange::kTorqueLimited : 0u);
  rec.recording_id = recording_;
  rec.mode = mode_;
  rec.seq = static_cast<std::uint64_t>(cycles_);
  rec.faults = supervisor_.latched();
  if (mode_ == Mode::Calibrate) calibration_.after_output(out, s.flags);

  // Transitions after the record is made: this record is the last of what ends.
  if (supervisor_.safe_state()) {
    if (recording_ != 0 || running()) end_recording(RecordingEnd::fault, rec);
    mode_ = Mode::Idle;  // nothing resumes by itself once the fault is cleared
  } else if (run_done) {
    end_recording(RecordingEnd::finished, rec);
  } else if (stop_pending_) {
    const Mode next = mode_after_stop_;
    end_recording(RecordingEnd::stopped, rec);
    if (next == Mode::Render) render_.reset();
    mode_ = next;
  } else if (stop_recording_pending_) {
    end_recording(RecordingEnd::finished, rec);
  }
  ++cycles_;

  const std::uint64_t packed = static_cast<std::uint64_t>(mode_) |
                               (static_cast<std::uint64_t>(supervisor_.latched() & 0xffffff) << 8) |
                               (static_cast<std::uint64_t>(recording_) << 32);
  published_.store(packed, std::memory_order_release);
  published_cycles_.store(cycles_, std::memory_order_relaxed);
  published_presses_.store(ctx.lines.capture_presses, std::memory_order_relaxed);
}

}  // namespace knoblab::hapticd
