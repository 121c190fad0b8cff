// HapticCore: what one loop cycle does, whatever paces it. The realtime
// daemon runs it under rt::PeriodicLoop; `knoblab simulate` runs the same
// object back to back in simulated time. Modes are small controllers (idle,
// render, capture, calibrate); the supervisor has the last word on every output.
//
// Modes and recordings are one state machine (every row is tested):
//
//   event               Idle / Render                Capture / Calibrate (a run)
//   set_mode idle|render that mode                   ends the run (stopped), then that mode
//   start_capture/-cal  the run starts (recording;   ignored: one run at a time
//                       a trial recording ends first)
//   stop_capture        nothing                      ends the run (stopped) → Idle
//   start_trial         a recording starts           ignored (the run records)
//   stop_trial          the recording ends           ignored
//   run's last cycle    –                            ends the run (finished) → Idle
//   a fault latches     → Idle; a recording ends     ends the run (fault) → Idle
//                       (fault)
//   while faulted       render, runs and trials are refused; clear_fault first
//   set_calibration     the sensors' constants       ignored (a run records)
//                       change (ignored while a trial records)
//
// A recording's last record says how it ended (LoopRecord::end). Commands that
// end a run take effect at the end of the cycle they arrive in, so that cycle
// is the run's last record and carries the reason.
//
// Threads: commands arrive from non-realtime code through a lock-free queue
// (post()); state leaves through atomics (state()). cycle() never allocates,
// locks or blocks.
#pragma once

#include <atomic>
#include <cstdint>

#include "knoblab/capture/capture_controller.hpp"
#include "knoblab/capture/daq.hpp"
#include "knoblab/capture/sample.hpp"
#include "knoblab/capture/sensor_front_end.hpp"
#include "knoblab/hapticd/calibration_controller.hpp"
#include "knoblab/hapticd/render_controller.hpp"
#include "knoblab/hapticd/supervisor.hpp"
#include "knoblab/rt/seqlock.hpp"
#include "knoblab/rt/spsc_ring.hpp"

namespace knoblab::hapticd {

enum class Mode : std::uint8_t { Idle, Render, Capture, Calibrate };
const char* to_string(Mode m);

// Digital inputs as the loop sees them (already active-high logic).
struct LineInputs {
  bool estop = false;
  bool capture_button = false;
  std::uint64_t capture_presses = 0;  // since start (the lines count them, debounced)
};

// What non-realtime code asks of the loop. Trivially copyable: it travels
// through a lock-free ring. A capture controller is built (which allocates)
// by the sender, not by the loop.
struct CoreCommand {
  enum Kind : std::uint8_t { SetMode, StartCapture, StopCapture, SetRender, StartRecording,
                             StopRecording, ClearFault, ForceSafe, StartCalibration,
                             SetSensorCalibration } kind = SetMode;
  Mode mode = Mode::Idle;
  bool immediate = false;
  RenderParams render{};
  capture::CaptureController capture{};
  std::int64_t capture_cycles = 0;
  // StartCalibration: a prebuilt controller; it runs calibration.cycles()
  // cycles (StopCapture ends it early), then the core is Idle again and
  // last_calibration() holds what it accumulated.
  CalibrationController calibration{};
  std::uint32_t faults = kFaultCommanded;  // ForceSafe: why (e.g. kFaultWatchdog)
  // SetSensorCalibration: the front end's constants from the next cycle on.
  // Ignored while anything records, so no recording mixes two calibrations.
  capture::SensorCalibration sensors{};
  // StartCapture / StartCalibration / StartRecording: the recording's id, so
  // the sender can describe it to the recorder first (0: the core numbers
  // it; a sender either always chooses ids, increasing, or never does).
  std::uint32_t recording_id = 0;
};

// How a recording ended, on its last record (none on every other record).
enum class RecordingEnd : std::uint8_t { none, finished, stopped, fault };
const char* to_string(RecordingEnd e);

// One loop cycle's record: the sample and whether it belongs to a recording.
struct LoopRecord {
  capture::Sample sample;
  std::int64_t now_ns = 0;         // CLOCK_MONOTONIC at the cycle's start (0 in simulated time)
  std::uint64_t seq = 0;           // the cycle's number: a gap means the ring lost records
  std::uint32_t recording_id = 0;  // 0: not recording; else which recording
  std::uint32_t faults = 0;        // Fault bits latched after this cycle's supervisor
  Mode mode = Mode::Idle;
  RecordingEnd end = RecordingEnd::none;  // set on the last record of a recording
};

// What the world says this cycle besides the DAQ's readings.
struct CycleContext {
  LineInputs lines{};
  std::int64_t consecutive_overruns = 0;
  std::uint32_t external_faults = 0;  // Fault bits that hold now (the amplifier over Modbus)
  // This cycle's DAQ and line reads, and the previous cycle's writes, all
  // succeeded. Consecutive failures latch `io` (SafetyLimits).
  bool io_ok = true;
};

struct CoreState {
  Mode mode = Mode::Idle;
  std::uint32_t faults = 0;        // latched Fault bits
  std::uint32_t recording_id = 0;  // 0 when not recording
  std::int64_t cycles = 0;
  // Capture-button presses since start. Only counted here: what a press
  // means is the front-end's choice (the control handler publishes it).
  std::uint64_t button_presses = 0;
};

struct CoreConfig {
  double rate_hz = 10000.0;
  capture::SensorCalibration calibration{};
  SafetyLimits limits{};
  RenderConfig render{};  // rate and torque per volt are taken from above
};

class HapticCore {
 public:
  explicit HapticCore(const CoreConfig& cfg);

  // Non-realtime side. False when the queue is full (retry later).
  bool post(const CoreCommand& c) { return commands_.try_push(c); }
  // Any thread, never fails and never waits (no queue to fill): the loop
  // latches these fault bits at its next cycle and the supervisor makes the
  // motor safe in it, as a ForceSafe command would. For the watchdog and
  // the store's refusal, which must not be lost behind a full queue.
  void request_safe(std::uint32_t faults) noexcept { safe_requests_.fetch_or(faults, std::memory_order_release); }
  // Prototyper tiles rendered on top of the model from the next cycle on
  // (nullptr clears them). False while the loop has not yet taken the
  // previous set (it does so every cycle); `tiles` then stays with the
  // caller: retry after a cycle.
  bool load_tiles(std::unique_ptr<TileSet>&& tiles) { return render_.load_tiles(std::move(tiles)); }
  CoreState state() const;
  // The sensor constants the front end uses (changed by SetSensorCalibration).
  capture::SensorCalibration sensor_calibration() const { return sensor_calibration_.read(); }
  // The data of the most recently ended calibration run, and how many runs
  // have ended so far (0: none yet; version changes when a new one ends).
  CalibrationData last_calibration() const { return calibration_result_.read(); }
  std::uint64_t calibrations_finished() const { return calibration_result_.version(); }

  // Realtime side: one cycle.
  void cycle(const capture::DaqInputs& in, const CycleContext& ctx, capture::DaqOutputs& out,
             LoopRecord& record);

  const CoreConfig& config() const { return cfg_; }

 private:
  void apply(const CoreCommand& c);
  bool running() const { return mode_ == Mode::Capture || mode_ == Mode::Calibrate; }
  void begin_recording(std::uint32_t id);
  // Ends the open recording (and a run) on this cycle's record.
  void end_recording(RecordingEnd why, LoopRecord& rec);
  void measure_idle(const capture::SensorReading& in, capture::Sample& s);

  CoreConfig cfg_;
  capture::SensorFrontEnd sensors_;  // every cycle, before the mode
  rt::SpscRing<CoreCommand, 16> commands_;
  CoreCommand pop_slot_{};  // where the loop receives commands
  RenderController render_;
  capture::CaptureController capture_;
  std::int64_t capture_left_ = 0;
  CalibrationController calibration_{};
  std::int64_t calibration_left_ = 0;
  rt::Seqlock<CalibrationData> calibration_result_{};
  rt::Seqlock<capture::SensorCalibration> sensor_calibration_{};
  Supervisor supervisor_;
  Mode mode_ = Mode::Idle;
  bool clear_requested_ = false;
  std::uint32_t forced_ = 0;
  std::atomic<std::uint32_t> safe_requests_{0};  // request_safe(), taken every cycle
  // A stop that arrived this cycle: applied after the cycle's record is made.
  bool stop_pending_ = false;
  Mode mode_after_stop_ = Mode::Idle;
  bool stop_recording_pending_ = false;
  int io_errors_in_a_row_ = 0;
  std::uint32_t recording_ = 0, next_recording_ = 1;
  std::int64_t cycles_ = 0;
  std::atomic<std::uint64_t> published_{0};  // mode | faults | recording, see state()
  std::atomic<std::int64_t> published_cycles_{0};
  std::atomic<std::uint64_t> published_presses_{0};
};

}  // namespace knoblab::hapticd
