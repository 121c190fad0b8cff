#include "knoblab/hapticd/core.hpp"

namespace knoblab::hapticd {

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
  r.calibration = c.calibration;
  r.torque_per_volt = c.limits.torque_per_volt;
  return r;
}
}  // namespace

HapticCore::HapticCore(const CoreConfig& cfg)
    : cfg_(cfg), render_(render_config(cfg)), supervisor_(cfg.limits) {}

CoreState HapticCore::state() const {
  const std::uint64_t p = published_.load(std::memory_order_acquire);
  CoreState s;
  s.mode = static_cast<Mode>(p & 0xff);
  s.faults = static_cast<std::uint32_t>((p >> 8) & 0xffffff);
  s.recording_id = static_cast<std::uint32_t>(p >> 32);
  s.cycles = published_cycles_.load(std::memory_order_relaxed);
  return s;
}

void HapticCore::apply(const CoreCommand& c) {
  switch (c.kind) {
    case CoreCommand::SetMode:
      if (c.mode == Mode::Render && mode_ != Mode::Render) render_.reset();
      if (mode_ == Mode::Calibrate && c.mode != Mode::Calibrate) {  // leaving a run early
        calibration_result_.publish(calibration_.data());
        recording_ = 0;
      }
      // capture and calibration start only with their own commands
      if (c.mode != Mode::Capture && c.mode != Mode::Calibrate) mode_ = c.mode;
      break;
    case CoreCommand::SetRender:
      render_.set_params(c.render, c.immediate);
      break;
    case CoreCommand::StartCapture:
      capture_ = c.capture;
      capture_left_ = c.capture_cycles;
      mode_ = Mode::Capture;
      recording_ = next_recording_++;
      break;
    case CoreCommand::StopCapture:
      if (mode_ == Mode::Capture || mode_ == Mode::Calibrate) {
        if (mode_ == Mode::Calibrate) calibration_result_.publish(calibration_.data());  // incomplete
        mode_ = Mode::Idle;
        recording_ = 0;
      }
      break;
    case CoreCommand::StartCalibration:
      if (mode_ == Mode::Capture || mode_ == Mode::Calibrate) break;  // one run at a time
      calibration_ = c.calibration;
      calibration_left_ = calibration_.cycles();
      if (calibration_left_ <= 0) break;  // an empty controller: nothing to run
      mode_ = Mode::Calibrate;
      recording_ = next_recording_++;  // recorded like a capture
      break;
    case CoreCommand::StartRecording:
      if (recording_ == 0) recording_ = next_recording_++;
      break;
    case CoreCommand::StopRecording:
      if (mode_ != Mode::Capture && mode_ != Mode::Calibrate) recording_ = 0;
      break;
    case CoreCommand::ClearFault:
      clear_requested_ = true;
      forced_ = 0;
      break;
    case CoreCommand::ForceSafe:
      forced_ |= c.faults;
      break;
  }
}

void HapticCore::measure_idle(const capture::DaqInputs& in, capture::Sample& s) {
  const capture::SensorCalibration& cal = cfg_.calibration;
  s.t = static_cast<double>(cycles_) / cfg_.rate_hz;
  s.theta = cal.theta(in.encoder_counts);
  s.alpha = cal.alpha(in.accel_V, s.theta);
  s.torque = cal.torque(in.torque_V);
}

void HapticCore::cycle(const capture::DaqInputs& in, const LineInputs& lines,
                       std::int64_t consecutive_overruns, std::uint32_t external_faults,
                       capture::DaqOutputs& out, LoopRecord& rec) {
  // pop_slot_ is built once: a CoreCommand holds controllers whose default
  // construction designs filters (allocates), which the loop must not do.
  for (int i = 0; i < 4 && commands_.try_pop(pop_slot_); ++i) apply(pop_slot_);

  capture::Sample& s = rec.sample;
  s = {};
  rec.now_ns = 0;
  out = {};
  bool capture_done = false, calibration_done = false;
  switch (mode_) {
    case Mode::Idle:
      measure_idle(in, s);
      break;
    case Mode::Render:
      render_.update(in, out, s);
      break;
    case Mode::Capture:
      capture_.update(in, out, s);
      capture_done = --capture_left_ <= 0;
      break;
    case Mode::Calibrate:
      calibration_.update(in, out, s);
      calibration_done = --calibration_left_ <= 0;
      break;
  }

  SafetyInputs safety;
  safety.estop = lines.estop;
  safety.external_faults = external_faults | forced_;
  safety.omega = s.omega;
  safety.consecutive_overruns = static_cast<int>(consecutive_overruns);
  safety.clear_requested = clear_requested_;
  clear_requested_ = false;
  const bool limited = supervisor_.apply(safety, out);
  s.command = out.motor_command_V;

  s.flags = (out.amp_enable ? interchange::kAmpEnabled : 0u) | (lines.estop ? interchange::kEstopActive : 0u) |
            (supervisor_.safe_state() ? interchange::kFaultLatched : 0u) |
            (limited ? interchange::kTorqueLimited : 0u);
  rec.recording_id = recording_;
  rec.mode = mode_;
  rec.seq = static_cast<std::uint64_t>(cycles_);
  rec.faults = supervisor_.latched();
  if (mode_ == Mode::Calibrate) calibration_.after_output(out, s.flags);
  if (calibration_done) {
    calibration_result_.publish(calibration_.data());
    mode_ = Mode::Idle;
    recording_ = 0;
  }
  if (capture_done) {  // that was the capture's last sample
    mode_ = Mode::Idle;
    recording_ = 0;
  }
  ++cycles_;

  const std::uint64_t packed = static_cast<std::uint64_t>(mode_) |
                               (static_cast<std::uint64_t>(supervisor_.latched() & 0xffffff) << 8) |
                               (static_cast<std::uint64_t>(recording_) << 32);
  published_.store(packed, std::memory_order_release);
  published_cycles_.store(cycles_, std::memory_order_relaxed);
}

}  // namespace knoblab::hapticd
