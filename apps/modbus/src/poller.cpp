#include "knoblab/modbus/poller.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace knoblab::modbus {
namespace {

static_assert(std::atomic<std::uint32_t>::is_always_lock_free, "the realtime loop reads status_ lock-free");

constexpr std::size_t kMaxQueuedCommands = 16;
constexpr Millis kSupervisorPeriod{2};
constexpr std::uint32_t kLinksLost =
    status::kAmpCommsLost | status::kBiometricsLost | status::kBiometricsStale;

std::int64_t ns_of(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

std::int64_t ns_of(Millis d) { return std::chrono::duration_cast<std::chrono::nanoseconds>(d).count(); }

}  // namespace

// One transport: a connection plus its reconnect schedule.
struct Poller::Link {
  std::unique_ptr<Connection> connection;
  Clock::time_point next_attempt{};
  Millis backoff{};
};

Poller::Poller(PollerConfig config) : config_(std::move(config)), status_(kLinksLost) {
  if (auto problem = validate(config_)) {
    const std::string setting = problem->setting.empty() ? "" : problem->setting + ": ";
    throw std::invalid_argument("modbus poller: " + setting + problem->why);
  }
  auto link_for = [this](const ModbusEndpoint& e) -> Link* {
    for (auto& l : links_) {
      if (transport_key(l->connection->endpoint()) == transport_key(e)) return l.get();
    }
    ConnectionResult made = make_connection(e);
    if (!made.connection) throw std::invalid_argument("modbus poller: " + made.error);
    auto link = std::make_unique<Link>();
    link->connection = std::move(made.connection);
    link->backoff = config_.backoff_min;
    links_.push_back(std::move(link));
    return links_.back().get();
  };
  if (config_.poll_amplifier) amp_link_ = link_for(config_.amplifier);
  if (config_.poll_biometrics) bio_link_ = link_for(config_.biometrics);
}

Poller::~Poller() { stop(); }

void Poller::start() {
  {
    std::lock_guard lock(mutex_);
    if (running_) return;
    running_ = true;
    stop_ = false;
  }
  // The amplifier has a thread of its own so that nothing the box does (slow
  // answers, a hung peer, a long on_sample) holds its reads past
  // comms_timeout. Both devices on one link (two units on one RTU bus) stay
  // on one thread: the line carries one request at a time, so a second
  // thread would only queue behind the first, and a libmodbus context must
  // not be used from two threads. validate() counts that wait against the
  // watchdogs.
  const bool shared = amp_link_ != nullptr && amp_link_ == bio_link_;
  if (amp_link_) amp_thread_ = std::thread([this, shared] { run(true, shared); });
  if (bio_link_ && !shared) bio_thread_ = std::thread([this] { run(false, true); });
  supervisor_thread_ = std::thread([this] { supervise(); });
}

void Poller::stop() {
  {
    std::lock_guard lock(mutex_);
    if (!running_) return;
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread* t : {&amp_thread_, &bio_thread_, &supervisor_thread_}) {
    if (t->joinable()) t->join();
  }
  for (auto& l : links_) l->connection->close();
  status_.store(kLinksLost | (io_bits_.load() & status::kAmpFault), std::memory_order_release);
  std::lock_guard lock(mutex_);
  queue_.clear();  // not for a later start(): the operator's intent may have changed
  running_ = false;
}

bool Poller::submit(AmpCommand command) {
  if (command.kind == AmpCommand::Kind::set_current_limit &&
      !(command.current_limit >= 0.0 && command.current_limit <= amp::kPeakCurrent)) {
    std::lock_guard lock(mutex_);
    ++stats_.commands_rejected;
    return false;
  }
  {
    std::lock_guard lock(mutex_);
    if (!running_ || stop_ || !amp_link_ || queue_.size() >= kMaxQueuedCommands) {
      ++stats_.commands_rejected;
      return false;
    }
    queue_.push_back(command);
  }
  wake_.notify_all();
  return true;
}

PollerStats Poller::stats() const {
  std::lock_guard lock(mutex_);
  PollerStats s = stats_;
  s.samples_missed = sequencer_missed_;
  s.box_restarts = sequencer_restarts_;
  return s;
}

std::optional<AmplifierStatus> Poller::amplifier() const {
  std::lock_guard lock(mutex_);
  return last_amp_;
}

// ---- polling threads -------------------------------------------------------

void Poller::raise_priority() {
  if (config_.priority <= 0) return;
  sched_param sp{};
  sp.sched_priority = config_.priority;
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
  std::lock_guard lock(mutex_);
  if (err == 0) {
    stats_.realtime = true;
  } else {
    stats_.realtime = false;
    stats_.last_error = "SCHED_FIFO priority " + std::to_string(config_.priority) + " refused (" +
                        std::strerror(err) + "): polling at ordinary priority";
  }
}

void Poller::run(bool amplifier, bool biometrics) {
  raise_priority();
  auto next_amp = Clock::now();
  auto next_bio = next_amp;
  auto advance = [](Clock::time_point& next, Millis period) {
    next += period;
    // After a slow request, poll at once instead of catching up in a burst.
    if (const auto now = Clock::now(); next < now) next = now;
  };
  for (;;) {
    if (amplifier) run_commands();
    const auto now = Clock::now();
    if (amplifier && now >= next_amp) {
      poll_amplifier();
      advance(next_amp, config_.amplifier_period);
    }
    if (biometrics && now >= next_bio) {
      poll_biometrics();
      advance(next_bio, config_.biometrics_period);
    }
    auto wake_at = Clock::now() + Millis{100};
    if (amplifier) wake_at = std::min(wake_at, next_amp);
    if (biometrics) wake_at = std::min(wake_at, next_bio);
    std::unique_lock lock(mutex_);
    wake_.wait_until(lock, wake_at, [&] { return stop_ || (amplifier && !queue_.empty()); });
    if (stop_) return;
  }
}

bool Poller::stopping() const {
  std::lock_guard lock(mutex_);
  return stop_;
}

bool Poller::ensure_open(Link& link, Clock::time_point now) {
  if (link.connection->is_open()) return true;
  if (now < link.next_attempt) return false;
  const IoResult r = link.connection->connect();
  std::lock_guard lock(mutex_);
  if (r.ok()) {
    ++stats_.connects;
    return true;
  }
  ++stats_.connect_failures;
  stats_.last_error = r.message;
  link.next_attempt = now + link.backoff;
  link.backoff = std::min(link.backoff * 2, config_.backoff_max);
  return false;
}

void Poller::on_error(Link& link, const IoResult& r, bool amplifier) {
  const bool exception = r.kind == IoResult::Kind::exception;
  set_io_bit(amplifier ? status::kAmpException : status::kBiometricsException, exception);
  {
    std::lock_guard lock(mutex_);
    ++(amplifier ? stats_.amp_errors : stats_.bio_errors);
    if (exception) ++(amplifier ? stats_.amp_exceptions : stats_.bio_exceptions);
    stats_.last_error = r.message;
  }
  if (r.reconnect) {
    link.connection->close();
    link.next_attempt = Clock::now() + link.backoff;
    link.backoff = std::min(link.backoff * 2, config_.backoff_max);
  }
}

void Poller::note_error(const std::string& message) {
  std::lock_guard lock(mutex_);
  ++stats_.mismatches;
  stats_.last_error = message;
}

void Poller::set_io_bit(std::uint32_t bit, bool on) {
  if (on) {
    io_bits_.fetch_or(bit, std::memory_order_acq_rel);
  } else {
    io_bits_.fetch_and(~bit, std::memory_order_acq_rel);
  }
}

void Poller::poll_amplifier() {
  Link& link = *amp_link_;
  if (!ensure_open(link, Clock::now())) return;
  std::array<std::uint16_t, amp::kInputCount> regs{};
  const IoResult r = link.connection->read_input_registers(config_.amplifier.unit_id, 0, regs);
  if (!r.ok()) return on_error(link, r, true);
  const auto now = Clock::now();
  const auto s = decode_amplifier(regs);
  set_io_bit(status::kAmpMismatch, !s);
  if (!s) return note_error(describe(config_.amplifier) + ": not a map-version-1 amplifier");

  link.backoff = config_.backoff_min;
  // Fresh only if the amp's own heartbeat moved: a frozen drive behind a
  // live Modbus interface is as lost as a dead link.
  if (!last_heartbeat_ || *last_heartbeat_ != s->heartbeat) amp_fresh_ns_.store(ns_of(now));
  last_heartbeat_ = s->heartbeat;

  const bool in_grace = now - enabled_at_ < config_.enable_grace;
  set_io_bit(status::kAmpException, false);
  set_io_bit(status::kAmpFault, s->faults != 0);
  set_io_bit(status::kAmpEnabled, s->enabled());
  set_io_bit(status::kAmpDisabledUnexpectedly, commanded_enabled_ && !s->enabled() && !in_grace);
  std::lock_guard lock(mutex_);
  ++stats_.amp_reads;
  last_amp_ = s;
}

void Poller::poll_biometrics() {
  Link& link = *bio_link_;
  if (!ensure_open(link, Clock::now())) return;
  std::array<std::uint16_t, bio::kInputCount> regs{};
  const IoResult r = link.connection->read_input_registers(config_.biometrics.unit_id, 0, regs);
  if (!r.ok()) return on_error(link, r, false);
  const auto now = Clock::now();
  const auto snapshot = decode_biometrics(regs);
  set_io_bit(status::kBiometricsMismatch, !snapshot);
  if (!snapshot) return note_error(describe(config_.biometrics) + ": not a map-version-1 biometrics box");

  link.backoff = config_.backoff_min;
  set_io_bit(status::kBiometricsException, false);
  bio_ok_ns_.store(ns_of(now));
  if (!last_counter_ || *last_counter_ != snapshot->latest_counter) bio_advance_ns_.store(ns_of(now));
  last_counter_ = snapshot->latest_counter;
  if (snapshot->rate_hz > 0) bio_rate_hz_.store(snapshot->rate_hz);

  const SampleSequencer::Batch batch = sequencer_.accept(*snapshot);
  if (batch.count > 0) box_clock_.observe(batch.samples[batch.count - 1].box_time_ms, now);
  for (std::size_t i = 0; i < batch.count; ++i) {
    BiometricSample sample = batch.samples[i];
    sample.received = now;
    sample.taken = box_clock_.to_host(sample.box_time_ms);
    if (!config_.on_sample) continue;
    try {
      config_.on_sample(sample);
    } catch (const std::exception& e) {  // a consumer bug must not kill the polling thread
      std::lock_guard lock(mutex_);
      stats_.last_error = std::string("on_sample threw: ") + e.what();
    }
  }
  std::lock_guard lock(mutex_);
  ++stats_.bio_reads;
  stats_.samples_delivered += batch.count;
  sequencer_missed_ = sequencer_.missed();
  sequencer_restarts_ = sequencer_.restarts();
}

void Poller::run_commands() {
  std::deque<AmpCommand> pending;
  {
    std::lock_guard lock(mutex_);
    pending.swap(queue_);
  }
  if (pending.empty()) return;
  for (const AmpCommand& c : pending) {
    if (stopping()) return;  // a hung amp would hold stop() one response timeout per command
    const bool ok = execute(c);
    std::lock_guard lock(mutex_);
    ++(ok ? stats_.commands_done : stats_.commands_failed);
  }
  // Read the result back at once so the status word reflects the command.
  poll_amplifier();
}

bool Poller::execute(const AmpCommand& c) {
  Link& link = *amp_link_;
  if (c.kind == AmpCommand::Kind::disable) commanded_enabled_ = false;  // the intent counts
  if (!ensure_open(link, Clock::now())) return false;
  const int unit = config_.amplifier.unit_id;
  IoResult r;
  switch (c.kind) {
    case AmpCommand::Kind::enable:
      r = link.connection->write_register(unit, amp::kEnableCommand, 1);
      if (r.ok()) {
        commanded_enabled_ = true;
        enabled_at_ = Clock::now();
      }
      break;
    case AmpCommand::Kind::disable:
      r = link.connection->write_register(unit, amp::kEnableCommand, 0);
      break;
    case AmpCommand::Kind::set_current_limit:
      r = link.connection->write_register(unit, amp::kCurrentLimitCommand,
                                          to_u16(c.current_limit, amp::kAmpsPerLsb));
      break;
    case AmpCommand::Kind::clear_faults:
      r = link.connection->write_register(unit, amp::kFaultReset, 1);
      break;
  }
  if (!r.ok()) on_error(link, r, true);
  return r.ok();
}

// ---- supervisor thread -----------------------------------------------------

void Poller::supervise() {
  raise_priority();
  for (;;) {
    publish(Clock::now());
    std::unique_lock lock(mutex_);
    if (wake_.wait_for(lock, kSupervisorPeriod, [this] { return stop_; })) return;
  }
}

void Poller::publish(Clock::time_point now) {
  const std::int64_t t = ns_of(now);
  std::uint32_t word = io_bits_.load(std::memory_order_acquire) | status::kRunning;
  if (amp_link_ && t - amp_fresh_ns_.load() > ns_of(config_.comms_timeout)) word |= status::kAmpCommsLost;
  if (bio_link_) {
    if (t - bio_ok_ns_.load() > ns_of(config_.biometrics_timeout)) word |= status::kBiometricsLost;
    const std::int64_t sample_ns = 1'000'000'000 / std::max(1, bio_rate_hz_.load());
    if (t - bio_advance_ns_.load() > config_.stale_periods * sample_ns) word |= status::kBiometricsStale;
  }
  status_.store(word, std::memory_order_release);
}

}  // namespace knoblab::modbus
