#include "knoblab/hapticd/daemon.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <stdexcept>

#include "knoblab/control/server.hpp"
#include "knoblab/control/telemetry_writer.hpp"
#include "knoblab/hapticd/calibration_file.hpp"
#include "knoblab/hapticd/control_handler.hpp"
#include "knoblab/hapticd/status_led.hpp"
#include "knoblab/modbus/status_bits.hpp"
#include "knoblab/rt/os.hpp"
#include "knoblab/rt/spsc_ring.hpp"

namespace knoblab::hapticd {

// 2^16 records: 6.5 s of loop output at 10 kHz may wait for the writer.
using RecordRing = rt::SpscRing<LoopRecord, 1u << 16>;

struct Daemon::Impl {
  std::unique_ptr<RecordRing> ring = std::make_unique<RecordRing>();
  std::unique_ptr<control::TelemetryWriter> telemetry;
  std::unique_ptr<ControlHandler> handler;
  std::unique_ptr<control::Server> server;
  std::thread writer;  // ring → recorder, telemetry, events
  std::thread storer;  // recorder → store
  // The writer has closed the recorder (the loop is gone, its ring empty);
  // the store thread has written or given up everything and ended.
  std::atomic<bool> recorder_closed{false}, store_done{false};
};

namespace {

// The Modbus poller's SCHED_FIFO priority, this far below the loop's (80 → 50):
// above ordinary work, never in the loop's way.
constexpr int kPollerPriorityBelowLoop = 30;

// Amplifier status over Modbus → the supervisor's fault bits. Biometrics
// problems are not faults: the box never stops the motor.
std::uint32_t faults_from_modbus(std::uint32_t word) {
  std::uint32_t f = 0;
  if (word & modbus::status::kAmpFault) f |= kFaultAmplifier;
  if (word & (modbus::status::kAmpCommsLost | modbus::status::kAmpDisabledUnexpectedly |
              modbus::status::kAmpMismatch))
    f |= kFaultAmpComms;
  return f;
}

}  // namespace

Daemon::Daemon(DaemonConfig cfg, std::unique_ptr<capture::Daq> daq, std::unique_ptr<hal::DigitalLines> lines)
    : cfg_(std::move(cfg)),
      daq_(std::move(daq)),
      lines_(std::move(lines)),
      core_(std::make_unique<HapticCore>(cfg_.core)),
      impl_(std::make_unique<Impl>()),
      stats_(std::make_unique<rt::StatsPublisher>()),
      accepted_(cfg_.accepted_calibrations) {
  if (!daq_) throw std::invalid_argument("hapticd: no DAQ backend");
  if (!lines_) throw std::invalid_argument("hapticd: no digital-lines backend");
  cfg_.loop.rate_hz = cfg_.core.rate_hz;
  rt::validate(cfg_.loop);
  if (!cfg_.db.empty()) store_.emplace(store::Store::open(cfg_.db));
  store::NewCapture defaults;
  defaults.knob = cfg_.knob;
  defaults.rate_hz = cfg_.core.rate_hz;
  defaults.calibration = cfg_.core.calibration.to_json();
  defaults.source = "hapticd";
  recorder_ = std::make_unique<Recorder>(store_ ? &*store_ : nullptr, defaults, cfg_.recorder);
  if (!cfg_.telemetry_shm.empty()) {
    control::TelemetryConfig t;
    t.shm_name = cfg_.telemetry_shm;
    t.decimation = static_cast<std::uint32_t>(cfg_.telemetry_decimation);
    t.loop_rate_hz = cfg_.core.rate_hz;
    impl_->telemetry = std::make_unique<control::TelemetryWriter>(t);
  }
  if (cfg_.modbus) {
    modbus::PollerConfig pc = *cfg_.modbus;
    // The poller's threads run realtime below the loop (its comms watchdog
    // must not trip on a busy machine), unless the config chose a priority.
    if (pc.priority == 0) pc.priority = std::max(1, cfg_.loop.priority - kPollerPriorityBelowLoop);
    pc.on_sample = [this](const modbus::BiometricSample& b) {
      store::BiometricSample s;
      s.seq = static_cast<std::int64_t>(b.counter);
      // Steady clock = CLOCK_MONOTONIC, the loop's clock; the recorder rebases it.
      s.t = std::chrono::duration<double>(b.taken.time_since_epoch()).count();
      s.emg_corrugator = b.emg_corrugator;
      s.emg_depressor = b.emg_depressor;
      s.skin_conductance = b.skin_conductance;
      recorder_->add_biometrics(s);
    };
    poller_ = std::make_unique<modbus::Poller>(std::move(pc));
  }
  if (cfg_.initial_model) {
    CoreCommand c;
    c.kind = CoreCommand::SetRender;
    c.immediate = true;
    c.render = *cfg_.initial_model;
    post(c);
  }
  if (!cfg_.socket_path.empty()) {
    impl_->handler = std::make_unique<ControlHandler>(*this, cfg_.initial_model.value_or(RenderParams{}));
    control::ServerConfig sc;
    sc.socket_path = cfg_.socket_path;
    sc.socket_group = cfg_.socket_group;
    sc.telemetry_shm = cfg_.telemetry_shm;
    impl_->server = std::make_unique<control::Server>(sc, *impl_->handler);
  }
}

Daemon::~Daemon() {
  stop_.store(true);
  loop_done_.store(true, std::memory_order_release);
  if (impl_->server) impl_->server->stop();
  if (poller_) poller_->stop();
  if (impl_->writer.joinable()) impl_->writer.join();
  if (impl_->storer.joinable()) impl_->storer.join();
}

bool Daemon::post(const CoreCommand& c) {
  std::lock_guard lock(command_mutex_);
  for (int i = 0; i < 100; ++i) {  // the loop drains 4 per cycle: a full queue clears fast
    if (core_->post(c)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

void Daemon::force_safe(std::uint32_t why) noexcept { core_->request_safe(why); }

bool Daemon::start_capture(const capture::CaptureConfig& cc, double seconds, const CaptureLabels& labels,
                           std::string& why) {
  const CoreState s = core_->state();
  if (s.faults != 0) {
    why = "a fault is latched; clear it first";
    return false;
  }
  if (s.mode == Mode::Capture || s.recording_id != 0) {
    why = "a capture or recording is already running";
    return false;
  }
  store::NewCapture info;
  info.knob = labels.knob.empty() ? cfg_.knob : labels.knob;
  info.mode = labels.mounting;
  if (!labels.metadata.empty()) info.metadata = labels.metadata.dump();
  info.rate_hz = cfg_.core.rate_hz;
  info.calibration = sensor_calibration().to_json();
  const bool torque = cc.kind == capture::CaptureConfig::Stimulus::Torque;
  const model::ChirpPhase ch = torque ? cc.torque_stimulus.chirp() : cc.stimulus.chirp();
  info.stimulus = nlohmann::json{{"kind", torque ? "torque_sweep" : "swept_sine"}, {"equation", 8},
                                 {"a", ch.a}, {"b", ch.b}, {"c", torque ? cc.torque_stimulus.amplitude_Nm : cc.stimulus.c},
                                 {"d", ch.d}}.dump();
  info.source = "hapticd";
  CoreCommand c;
  c.kind = CoreCommand::StartCapture;
  c.recording_id = next_recording_id_.fetch_add(1);
  recorder_->describe(c.recording_id, info, RecordingKind::stimulus);
  capture::CaptureConfig full = cc;
  full.rate_hz = cfg_.core.rate_hz;
  c.capture = capture::CaptureController(full);
  c.capture_cycles = static_cast<std::int64_t>(std::llround(seconds * cfg_.core.rate_hz));
  if (!post(c)) {
    why = "the loop is not taking commands";
    return false;
  }
  return true;
}

bool Daemon::start_calibration(const CalibrationConfig& cfg, double& seconds, std::string& why) {
  const CoreState s = core_->state();
  if (s.faults != 0) {
    why = "a fault is latched; clear it first";
    return false;
  }
  if (s.mode == Mode::Capture || s.mode == Mode::Calibrate || s.recording_id != 0) {
    why = "a capture, calibration or recording is already running";
    return false;
  }
  CalibrationConfig full = cfg;
  full.rate_hz = cfg_.core.rate_hz;
  full.calibration = sensor_calibration();
  full.torque_per_volt = cfg_.core.limits.torque_per_volt;
  CoreCommand c;
  c.kind = CoreCommand::StartCalibration;
  try {
    c.calibration = CalibrationController(full);
  } catch (const std::exception& e) {
    why = e.what();
    return false;
  }
  store::NewCapture info;
  info.rate_hz = cfg_.core.rate_hz;
  info.calibration = full.calibration.to_json();
  info.source = "hapticd";
  info.metadata = std::string(R"({"calibration":")") + to_string(full.kind) + "\"}";
  c.recording_id = next_recording_id_.fetch_add(1);
  recorder_->describe(c.recording_id, info, RecordingKind::calibration);
  if (!post(c)) {
    why = "the loop is not taking commands";
    return false;
  }
  seconds = c.calibration.seconds();
  return true;
}

std::optional<std::uint32_t> Daemon::start_trial(const nlohmann::json& trial, std::string& why) {
  const CoreState s = core_->state();
  if (s.faults != 0) {
    why = "a fault is latched (" + fault_list(s.faults) + "); clear_fault first";
    return std::nullopt;
  }
  if (s.recording_id != 0 || s.mode == Mode::Capture || s.mode == Mode::Calibrate) {
    why = "a capture, calibration or trial is already recording";
    return std::nullopt;
  }
  store::NewCapture info;
  info.knob = cfg_.knob;
  info.rate_hz = cfg_.core.rate_hz;
  info.calibration = sensor_calibration().to_json();
  info.source = "hapticd";
  info.metadata = nlohmann::json{{"trial", trial}}.dump();
  CoreCommand c;
  c.kind = CoreCommand::StartRecording;
  c.recording_id = next_recording_id_.fetch_add(1);
  recorder_->describe(c.recording_id, info, RecordingKind::trial);
  if (!post(c)) {
    why = "the loop is not taking commands";
    return std::nullopt;
  }
  return c.recording_id;
}

std::optional<CalibrationResult> Daemon::last_calibration() const {
  std::lock_guard lock(calibration_mutex_);
  if (calibration_history_.empty()) return std::nullopt;
  return calibration_history_.back();
}

std::optional<CalibrationResult> Daemon::take_finished_calibration() {
  std::lock_guard lock(calibration_mutex_);
  std::optional<CalibrationResult> out;
  out.swap(unpublished_calibration_);
  return out;
}

void Daemon::collect_finished_calibrations() {
  const std::uint64_t n = core_->calibrations_finished();
  if (n == calibrations_seen_) return;
  calibrations_seen_ = n;
  CalibrationResult r = evaluate(core_->last_calibration());  // solves small systems: outside the lock
  std::lock_guard lock(calibration_mutex_);
  // Enough for three repetitions of every kind, with retries.
  constexpr std::size_t kKeep = 32;
  if (calibration_history_.size() == kKeep) calibration_history_.erase(calibration_history_.begin());
  calibration_history_.push_back(r);
  unpublished_calibration_ = std::move(r);
}

nlohmann::json Daemon::accepted_calibrations() const {
  std::lock_guard lock(calibration_mutex_);
  return accepted_;
}

std::variant<AcceptedCalibration, std::string> Daemon::accept_calibration(CalibrationKind kind, int repetitions) {
  std::lock_guard accepting(accept_mutex_);
  const CoreState s = core_->state();
  if (s.recording_id != 0 || s.mode == Mode::Capture || s.mode == Mode::Calibrate)
    return std::string("a capture, calibration or trial is recording: accept once it has ended, so that no "
                       "recording mixes two calibrations");
  const capture::SensorCalibration before = core_->sensor_calibration();
  std::variant<AcceptedCalibration, std::string> averaged;
  {
    std::lock_guard lock(calibration_mutex_);
    averaged = average_runs(calibration_history_, kind, repetitions, before);
  }
  auto* a = std::get_if<AcceptedCalibration>(&averaged);
  if (!a) return averaged;
  a->unix_time = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();

  // Applied by the loop; it refuses if a recording started meanwhile.
  const auto apply = [this](const capture::SensorCalibration& c) {
    CoreCommand cmd;
    cmd.kind = CoreCommand::SetSensorCalibration;
    cmd.sensors = c;
    if (!post(cmd)) return false;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
    while (!(core_->sensor_calibration() == c)) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return true;
  };
  if (!apply(a->after)) return std::string("the loop did not take the new calibration (a recording started?)");

  nlohmann::json accepted;
  {
    std::lock_guard lock(calibration_mutex_);
    accepted = accepted_;
  }
  accepted[to_string(kind)] = to_json(*a);
  if (!cfg_.calibration_file.empty()) {
    try {
      write_calibration_file(cfg_.calibration_file, {a->after, accepted});
    } catch (const std::exception& e) {
      // Kept only if it survives a restart: go back to what the file says.
      (void)apply(before);
      return std::string("cannot save the calibration (") + e.what() + "); the previous one stays in use";
    }
  }
  std::lock_guard lock(calibration_mutex_);
  accepted_ = std::move(accepted);
  return averaged;
}

bool Daemon::clear_faults() {
  if (poller_ && (poller_->status() & modbus::status::kAmpTripMask)) {
    poller_->clear_faults();
    // Wait for a read that shows the amplifier's fault word cleared.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
    while ((poller_->status() & modbus::status::kAmpTripMask) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  CoreCommand c;
  c.kind = CoreCommand::ClearFault;
  return post(c);
}

std::vector<FinishedRecording> Daemon::finished() {
  std::lock_guard lock(finished_mutex_);
  std::vector<FinishedRecording> out;
  out.swap(finished_);
  return out;
}

std::uint32_t Daemon::modbus_status() const { return poller_ ? poller_->status() : 0; }

std::uint64_t Daemon::ring_dropped() const { return impl_->ring->dropped(); }

// The writer thread: ring → recorder, telemetry and events. It never waits
// for the store (the store thread does), so telemetry flows and the ring
// drains while a commit waits seconds for an fsync.
void Daemon::writer_main() {
  LoopRecord batch[512];
  for (;;) {
    const bool done = loop_done_.load(std::memory_order_acquire);
    const std::size_t n = impl_->ring->pop_bulk(batch);
    for (std::size_t i = 0; i < n; ++i) {
      const LoopRecord& r = batch[i];
      recorder_->take(r);
      if (impl_->telemetry) {
        control::TelemetrySample ts;
        ts.t = static_cast<double>(r.now_ns) * 1e-9;
        ts.theta = r.sample.theta;
        ts.omega = r.sample.omega;
        ts.torque = r.sample.torque;
        ts.command = -r.sample.command * cfg_.core.limits.torque_per_volt;
        ts.mode = static_cast<std::uint32_t>(r.mode);
        ts.fault_bits = r.sample.flags;
        impl_->telemetry->push(ts);
      }
    }
    if (done && n == 0 && !impl_->recorder_closed.load(std::memory_order_relaxed)) {
      recorder_->close();  // the loop is gone and its ring empty
      impl_->recorder_closed.store(true, std::memory_order_release);
    }
    if (recorder_->safe_state_needed()) {
      // A recording the store cannot take: the motor must not go on being
      // driven for it. The fault it latches ends the capture or recording
      // in the same cycle.
      force_safe(kFaultRecording);
    }
    collect_finished_calibrations();
    // Read before the finished list, so that nothing the store thread
    // finished before it ended is missed.
    const bool store_done = impl_->store_done.load(std::memory_order_acquire);
    auto fin = recorder_->take_finished();
    publish_events(fin);
    if (!fin.empty()) {
      std::lock_guard lock(finished_mutex_);
      finished_.insert(finished_.end(), fin.begin(), fin.end());
    }
    if (n == 0) {
      if (store_done) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
}

// The store thread: what the recorder took goes into the store, one commit
// per batch. Ends once the recorder is closed and everything is written, or
// when the store takes nothing for a long while after the loop stopped.
void Daemon::store_main() {
  // After the loop stopped: how long the store may go without taking any of
  // what is still buffered before hapticd gives it up and exits.
  constexpr auto kShutdownPatience = std::chrono::seconds(30);
  std::optional<std::chrono::steady_clock::time_point> give_up_at;
  std::uint64_t last_buffered = 0;
  for (;;) {
    const bool closed = impl_->recorder_closed.load(std::memory_order_acquire);
    recorder_->pump();
    if (closed) {
      if (recorder_->idle()) break;
      const std::uint64_t buffered = recorder_->stats().buffered;
      const auto now = std::chrono::steady_clock::now();
      if (!give_up_at || buffered < last_buffered) give_up_at = now + kShutdownPatience;
      last_buffered = buffered;
      if (now > *give_up_at) {
        std::fprintf(stderr, "hapticd: the store stayed busy; %llu samples not stored\n",
                     static_cast<unsigned long long>(buffered));
        recorder_->abandon_all("store busy at shutdown");
        break;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  impl_->store_done.store(true, std::memory_order_release);
}

RecorderStats Daemon::recorder_stats() const { return recorder_->stats(); }

void Daemon::publish_events(const std::vector<FinishedRecording>& finished) {
  if (impl_->handler && impl_->server) impl_->handler->publish_events(*impl_->server, finished);
}

namespace {

// The motor's safe state: zero command, amplifier enable low. Best effort by
// design: if the hardware cannot be written, nothing else can be done here
// (the amplifier's own enable input defaults low, and the image's watchdog
// and e-stop chain do not depend on this process).
void write_safe_outputs(capture::Daq& daq, hal::DigitalLines& lines) noexcept {
  (void)daq.write({});
  (void)lines.write({});
}

}  // namespace

// Whatever way run() leaves — a stop request, the cycle count, an exception
// from the loop or from starting a thread — this writes the safe state, lets
// the writer commit what it has and stops it, then stops the server and the
// poller. Without it an exception skipped all of that and ~Daemon waited
// forever for a writer nobody had told to finish.
class Daemon::RunGuard {
 public:
  explicit RunGuard(Daemon& d) : d_(d) {}
  RunGuard(const RunGuard&) = delete;
  RunGuard& operator=(const RunGuard&) = delete;
  ~RunGuard() {
    write_safe_outputs(*d_.daq_, *d_.lines_);
    d_.loop_done_.store(true, std::memory_order_release);
    // A thread that never started (run() threw first) is not waited for.
    Impl& i = *d_.impl_;
    if (!i.storer.joinable()) i.store_done.store(true, std::memory_order_release);
    if (!i.writer.joinable()) {
      d_.recorder_->close();
      i.recorder_closed.store(true, std::memory_order_release);
    }
    if (i.writer.joinable()) i.writer.join();
    if (i.storer.joinable()) i.storer.join();
    if (d_.impl_->server) d_.impl_->server->stop();
    if (d_.poller_) d_.poller_->stop();
  }

 private:
  Daemon& d_;
};

rt::LoopResult Daemon::run() {
  RunGuard guard(*this);
  if (poller_) {
    poller_->start();
    // The poller reports the amplifier lost until its first good read; give
    // it a moment so start-up does not latch a fault that isn't one. If the
    // amplifier stays silent, the loop starts in the safe state, as it must.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while ((poller_->status() & modbus::status::kAmpTripMask) != 0 &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (impl_->server) impl_->server->start();
  impl_->storer = std::thread([this] { store_main(); });
  impl_->writer = std::thread([this] { writer_main(); });

  capture::Daq& daq = *daq_;
  hal::DigitalLines& lines = *lines_;
  HapticCore& core = *core_;
  RecordRing& ring = *impl_->ring;
  const std::atomic<std::uint32_t>* amp_status = poller_ ? &poller_->status_word() : nullptr;
  bool writes_ok = true;  // the previous cycle's writes, judged in this cycle
  const double rate_hz = cfg_.core.rate_hz;

  return rt::run(
      cfg_.loop,
      [&](const rt::CycleInfo& info) {
        try {
          capture::DaqInputs in;
          hal::DigitalInputs din;
          const bool daq_ok = daq.read(in) == capture::IoStatus::ok;
          const bool lines_ok = lines.read(din) == capture::IoStatus::ok;
          CycleContext ctx;
          ctx.lines = {din.estop, din.capture_button, din.capture_presses};
          ctx.consecutive_overruns = info.consecutive_overruns;
          ctx.external_faults = amp_status ? faults_from_modbus(amp_status->load(std::memory_order_acquire)) : 0u;
          ctx.io_ok = daq_ok && lines_ok && writes_ok;
          capture::DaqOutputs out;
          LoopRecord rec;
          core.cycle(in, ctx, out, rec);
          const bool daq_written = daq.write(out) == capture::IoStatus::ok;
          const bool lines_written =
              lines.write({out.amp_enable, status_led(rec, rate_hz)}) == capture::IoStatus::ok;
          writes_ok = daq_written && lines_written;
          rec.now_ns = info.now_ns;
          ring.try_push(rec);
        } catch (...) {
          // The motor stops in this cycle, before the exception leaves the loop.
          write_safe_outputs(daq, lines);
          throw;
        }
      },
      stop_, stats_.get());
}

}  // namespace knoblab::hapticd
