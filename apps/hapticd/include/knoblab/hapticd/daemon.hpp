// hapticd put together: the realtime loop (rt::PeriodicLoop running
// HapticCore over a DAQ and digital lines) feeding a lock-free ring; a writer
// thread draining it into telemetry and the recorder, and a store thread
// committing the recorder's batches; the control server; the
// Modbus poller. Data flows one way: HAL → loop → ring → store / telemetry.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/capture/daq.hpp"
#include "knoblab/hal/digital_lines.hpp"
#include "knoblab/hapticd/calibration_acceptance.hpp"
#include "knoblab/hapticd/core.hpp"
#include "knoblab/hapticd/recorder.hpp"
#include "knoblab/hapticd/render_params.hpp"
#include "knoblab/modbus/poller.hpp"
#include "knoblab/rt/periodic_loop.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::control {
class Server;
class TelemetryWriter;
}  // namespace knoblab::control

namespace knoblab::hapticd {

struct DaemonConfig {
  rt::LoopConfig loop{};
  CoreConfig core{};
  std::filesystem::path db;           // store; empty = record nothing
  std::string socket_path;            // control socket; empty = no server
  std::string socket_group;
  std::string telemetry_shm;          // e.g. "/knoblab-telemetry"; empty = none
  std::size_t telemetry_decimation = 10;
  std::optional<modbus::PollerConfig> modbus;  // amplifier + biometrics; none = not wired
  std::string knob;                   // default knob name for captures
  // The sim backend's guided hand (its shared-memory channel), which a
  // simulated participant steers; empty: none (get_state's hand_channel).
  std::string hand_channel;
  // Render model loaded at start (hapticd --model FILE): rendered once the
  // mode is set to render, and the base later set_params calls change.
  std::optional<RenderParams> initial_model;
  // How recordings go into the store: among others the samples held while
  // the store is busy (max_buffered; beyond it the recording is cut and the
  // motor made safe; 0: 60 s at the loop rate) and how often they commit.
  RecorderOptions recorder{};
  // Where accepted calibrations are kept (calibration_file.hpp); empty: in
  // memory only. core.calibration is what it held at start, and
  // accepted_calibrations its record of what was accepted when.
  std::filesystem::path calibration_file;
  nlohmann::json accepted_calibrations = nlohmann::json::object();
};

// What a capture is stored under besides its samples: the knob, how the
// camera was mounted (the store's mode) and the experimenter's metadata
// (gripper, notes).
struct CaptureLabels {
  std::string knob;              // empty: the daemon's --knob
  std::string mounting = "lab";  // 'lab' | 'tripod'
  nlohmann::json metadata = nlohmann::json::object();
};

class Daemon {
 public:
  // The DAQ and lines are the HAL backends (sim or real), owned here.
  Daemon(DaemonConfig cfg, std::unique_ptr<capture::Daq> daq, std::unique_ptr<hal::DigitalLines> lines);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Runs the loop on its realtime thread until stop() (or max_cycles);
  // returns the loop's result once everything recorded is committed. Leaves
  // the motor safe (zero command, enable low) however it returns or throws.
  rt::LoopResult run();
  void stop() { stop_.store(true); }

  // --- non-realtime API (control handler, tests) ---
  HapticCore& core() { return *core_; }
  // Starts a swept-sine capture; returns false with a reason when it can't.
  bool start_capture(const capture::CaptureConfig& cfg, double seconds, const CaptureLabels& labels,
                     std::string& why);
  bool start_capture(const capture::CaptureConfig& cfg, double seconds, const std::string& knob, std::string& why) {
    return start_capture(cfg, seconds, CaptureLabels{knob, "lab", nlohmann::json::object()}, why);
  }
  bool post(const CoreCommand& c);
  // The motor safe from the loop's next cycle, latching `why` (Fault bits):
  // from any thread, and it cannot be lost, however full the command queue.
  void force_safe(std::uint32_t why) noexcept;
  // Starts a calibration run (kinds: see calibration_controller.hpp). The
  // loop's rate, the sensor calibration in use and the torque-per-volt come
  // from the daemon's config; the rest (durations, PID) from `cfg`. The run
  // is recorded like a capture (no knob, metadata {"calibration": kind}).
  // Returns false with a reason when it can't; on success `seconds` = how
  // long the run takes.
  bool start_calibration(const CalibrationConfig& cfg, double& seconds, std::string& why);
  // Starts a study trial: a recording of whatever the mode does until
  // stop_trial, stored with `trial` (study, participant, condition) in its
  // metadata. Returns its recording id, or nullopt with a reason.
  std::optional<std::uint32_t> start_trial(const nlohmann::json& trial, std::string& why);
  // The most recently ended calibration, fitted (nullopt: none has ended).
  std::optional<CalibrationResult> last_calibration() const;
  // Each ended calibration once (for the event publisher): nullopt when no
  // new one has ended since the previous call.
  std::optional<CalibrationResult> take_finished_calibration();
  // Averages the latest `repetitions` good runs of `kind` and makes the
  // result the sensors' calibration (saved to the calibration file first
  // when there is one). Refused while anything records. The accepted
  // calibration, or why not (a sentence for the user).
  std::variant<AcceptedCalibration, std::string> accept_calibration(CalibrationKind kind, int repetitions);
  // The sensor constants in use, and the record of accepted calibrations.
  capture::SensorCalibration sensor_calibration() const { return core_->sensor_calibration(); }
  nlohmann::json accepted_calibrations() const;
  // Clears latched faults whose cause is gone: first the amplifier's own
  // (over Modbus), then the supervisor's.
  bool clear_faults();
  std::vector<FinishedRecording> finished();
  std::uint32_t modbus_status() const;
  const DaemonConfig& config() const { return cfg_; }
  const rt::StatsPublisher& stats() const { return *stats_; }
  std::uint64_t ring_dropped() const;
  // What the recorder holds for a busy store, and how often it had to retry.
  RecorderStats recorder_stats() const;

 private:
  struct Impl;
  class RunGuard;
  void writer_main();
  void store_main();
  void publish_events(const std::vector<FinishedRecording>& finished);
  // Writer thread: fits each calibration run that ended into the history.
  void collect_finished_calibrations();

  DaemonConfig cfg_;
  std::unique_ptr<capture::Daq> daq_;
  std::unique_ptr<hal::DigitalLines> lines_;
  std::unique_ptr<HapticCore> core_;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<rt::StatsPublisher> stats_;
  std::optional<store::Store> store_;
  std::unique_ptr<Recorder> recorder_;
  std::unique_ptr<modbus::Poller> poller_;
  std::atomic<bool> stop_{false}, loop_done_{false};
  std::mutex finished_mutex_;
  std::vector<FinishedRecording> finished_;
  std::mutex command_mutex_;  // post() from several non-RT threads
  mutable std::mutex calibration_mutex_;
  std::uint64_t calibrations_seen_ = 0;                 // writer thread only
  std::vector<CalibrationResult> calibration_history_;  // oldest first, bounded
  std::optional<CalibrationResult> unpublished_calibration_;
  nlohmann::json accepted_;  // kind → the accept record (cfg_.accepted_calibrations at start)
  std::mutex accept_mutex_;  // one accept at a time
  // Recording ids, chosen here so each is described to the recorder before
  // the loop starts it.
  std::atomic<std::uint32_t> next_recording_id_{1};
};

}  // namespace knoblab::hapticd
