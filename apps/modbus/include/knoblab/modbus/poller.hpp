// The hapticd side of Modbus: non-realtime threads that poll the servo
// amplifier and the biometrics box, run queued amplifier commands and
// reconnect with backoff. Each device is polled on its own thread, so a slow
// or hung biometrics box cannot hold amplifier reads past the comms
// watchdog; a supervisor thread publishes the status word. The realtime loop
// only ever reads status(), one lock-free atomic load; nothing here blocks
// or allocates on its behalf.
//
//   Poller poller(config);              // throws std::invalid_argument on bad config
//   poller.start();
//   … loop, each cycle:  if (poller.status() & status::kAmpTripMask) zero_torque();
//   … UI / session code: poller.enable(); poller.set_current_limit(5.0);
//   poller.stop();                      // joins within ~1 response timeout
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "knoblab/modbus/box_clock.hpp"
#include "knoblab/modbus/codec.hpp"
#include "knoblab/modbus/connection.hpp"
#include "knoblab/modbus/endpoint.hpp"
#include "knoblab/modbus/sample_sequencer.hpp"
#include "knoblab/modbus/status_bits.hpp"

namespace knoblab::modbus {

using Millis = std::chrono::milliseconds;

struct PollerConfig {
  ModbusEndpoint amplifier = default_endpoint(kDefaultAmplifierUnit);
  ModbusEndpoint biometrics = default_endpoint(kDefaultBiometricsUnit);
  bool poll_amplifier = true;
  bool poll_biometrics = true;

  Millis amplifier_period{10};   // 100 Hz
  Millis biometrics_period{10};  // must be <= 15 ms: >= 64 Hz, twice the box's 32 Hz
  // Each watchdog must exceed its device's period + response_timeout, or one
  // unanswered request would raise it (validate(), below).
  Millis comms_timeout{50};      // no fresh amp read for this long -> kAmpCommsLost
  Millis biometrics_timeout{100};// no biometrics read for this long -> kBiometricsLost
  int stale_periods = 3;         // counter still for more sample periods -> kBiometricsStale
  Millis enable_grace{50};       // after enabling, time the amp gets to report it
  Millis backoff_min{20};        // reconnect delay, doubling per failure …
  Millis backoff_max{500};       // … up to this
  // SCHED_FIFO priority of the poller's threads (0: ordinary scheduling).
  // Below the realtime loop's, above everything else: the comms watchdog
  // above must not trip because a busy machine starved the thread reading.
  int priority = 0;

  // Called on the biometrics thread with each 32 Hz sample exactly once, in
  // counter order. Keep it short (queue to the store): it delays polling the
  // box, and on a shared RTU bus the amplifier too (one thread polls both).
  // An exception it throws is caught and lands in PollerStats::last_error.
  std::function<void(const BiometricSample&)> on_sample;

  static ModbusEndpoint default_endpoint(int unit) {
    ModbusEndpoint e;
    e.unit_id = unit;
    return e;
  }
};

// A PollerConfig setting that cannot work: its member path
// ("amplifier.response_timeout", "comms_timeout"; empty for the whole) and why.
struct PollerConfigProblem {
  std::string setting;
  std::string why;
};

// The first problem with c, or nullopt: the endpoints (validate(endpoint)),
// the periods, and the timing rules: period + response_timeout below the
// device's watchdog; devices on one RTU bus at distinct unit ids with the
// same line settings and response timeout. Poller's constructor throws
// std::invalid_argument("modbus poller: SETTING: WHY") for it. docs/modbus.md.
std::optional<PollerConfigProblem> validate(const PollerConfig& c);

struct PollerStats {
  std::uint64_t amp_reads = 0, amp_errors = 0, amp_exceptions = 0;
  std::uint64_t bio_reads = 0, bio_errors = 0, bio_exceptions = 0;
  std::uint64_t samples_delivered = 0, samples_missed = 0, box_restarts = 0;
  std::uint64_t connects = 0, connect_failures = 0, mismatches = 0;
  std::uint64_t commands_done = 0, commands_failed = 0, commands_rejected = 0;
  std::string last_error;
  bool realtime = false;  // the threads run at PollerConfig::priority (SCHED_FIFO)
};

struct AmpCommand {
  enum class Kind { enable, disable, set_current_limit, clear_faults };
  Kind kind = Kind::disable;
  double current_limit = 0.0;  // A, for set_current_limit
};

class Poller {
 public:
  explicit Poller(PollerConfig config);
  ~Poller();
  Poller(const Poller&) = delete;
  Poller& operator=(const Poller&) = delete;

  void start();
  // Joins the threads. Bounded: each polling thread is at most inside one
  // request (its response_timeout) when asked, and they finish it side by
  // side; queued commands not yet sent are dropped.
  void stop();

  // Realtime-safe: one atomic load. Before start() and after stop() it
  // reports the links lost (fail-safe).
  std::uint32_t status() const noexcept { return status_.load(std::memory_order_acquire); }
  const std::atomic<std::uint32_t>& status_word() const noexcept { return status_; }

  // Queue a command for the amplifier thread (non-realtime callers only).
  // False if the queue is full, the poller is not running or the value is
  // out of range (current limit outside 0..20 A, the amp's peak).
  bool enable() { return submit({AmpCommand::Kind::enable}); }
  bool disable() { return submit({AmpCommand::Kind::disable}); }
  bool set_current_limit(double amps) { return submit({AmpCommand::Kind::set_current_limit, amps}); }
  bool clear_faults() { return submit({AmpCommand::Kind::clear_faults}); }
  bool submit(AmpCommand command);

  PollerStats stats() const;
  std::optional<AmplifierStatus> amplifier() const;  // last good read

 private:
  using Clock = std::chrono::steady_clock;
  struct Link;

  void raise_priority();  // on each of its threads, as PollerConfig::priority asks
  void run(bool amplifier, bool biometrics);  // one polling thread's loop
  bool stopping() const;
  void supervise();
  void publish(Clock::time_point now);
  bool ensure_open(Link& link, Clock::time_point now);
  void on_error(Link& link, const IoResult& r, bool amplifier);
  void poll_amplifier();
  void poll_biometrics();
  void run_commands();
  bool execute(const AmpCommand& c);
  void set_io_bit(std::uint32_t bit, bool on);
  void note_error(const std::string& message);

  const PollerConfig config_;
  std::vector<std::unique_ptr<Link>> links_;
  Link* amp_link_ = nullptr;
  Link* bio_link_ = nullptr;

  std::atomic<std::uint32_t> status_;

  // Facts the polling threads learn; the supervisor turns them into status_
  // (it alone writes status_, so the word is always self-consistent).
  std::atomic<std::uint32_t> io_bits_{0};
  std::atomic<std::int64_t> amp_fresh_ns_{0};  // last read with the heartbeat moving
  std::atomic<std::int64_t> bio_ok_ns_{0};     // last good biometrics read
  std::atomic<std::int64_t> bio_advance_ns_{0};// last read with a new counter
  std::atomic<int> bio_rate_hz_{bio::kRateHz};

  // Biometrics-thread-only state.
  SampleSequencer sequencer_;
  BoxClock box_clock_;
  std::optional<std::uint32_t> last_counter_;
  // Amplifier-thread-only state.
  std::optional<std::uint16_t> last_heartbeat_;
  bool commanded_enabled_ = false;
  Clock::time_point enabled_at_{};

  mutable std::mutex mutex_;  // queue_, stop_, stats_, last_amp_
  std::condition_variable wake_;
  std::deque<AmpCommand> queue_;
  bool stop_ = false;
  bool running_ = false;
  PollerStats stats_;
  std::uint64_t sequencer_missed_ = 0;
  std::uint64_t sequencer_restarts_ = 0;
  std::optional<AmplifierStatus> last_amp_;

  std::thread amp_thread_;  // the amplifier and its commands (and the box, on a shared link)
  std::thread bio_thread_;  // the biometrics box, when it has a link of its own
  std::thread supervisor_thread_;
};

}  // namespace knoblab::modbus
