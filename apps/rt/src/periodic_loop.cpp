// The non-template half of PeriodicLoop: config checks, thread start/join,
// realtime setup, and turning the thread's report into a result.
#include "knoblab/rt/periodic_loop.hpp"

#include <pthread.h>
#include <sched.h>

#include <cerrno>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace knoblab::rt {

namespace {

// The loop thread's stack: room for TimingStats copies and a controller's
// locals; mlockall keeps it resident.
constexpr std::size_t kLoopStackBytes = 2 * 1024 * 1024;

struct Trampoline {
  void (*body)(void*);
  void* arg;
};

void* start_routine(void* p) {
  auto* t = static_cast<Trampoline*>(p);
  t->body(t->arg);
  return nullptr;
}

std::string status_text(const Status& s) { return s.message(); }

}  // namespace

void validate(const LoopConfig& c) {
  if (!std::isfinite(c.rate_hz) || c.rate_hz < 1.0 || c.rate_hz > 20000.0)
    throw std::invalid_argument("LoopConfig::rate_hz must be within 1..20000 Hz, got " +
                                std::to_string(c.rate_hz));
  const int lo = sched_get_priority_min(SCHED_FIFO);
  const int hi = sched_get_priority_max(SCHED_FIFO);
  if (c.priority < lo || c.priority > hi)
    throw std::invalid_argument("LoopConfig::priority must be within " + std::to_string(lo) +
                                ".." + std::to_string(hi) + ", got " + std::to_string(c.priority));
  if (c.cpu < -1 || c.cpu >= CPU_SETSIZE)
    throw std::invalid_argument("LoopConfig::cpu must be -1 (no pinning) or a CPU number, got " +
                                std::to_string(c.cpu));
  if (c.max_cycles < -1)
    throw std::invalid_argument("LoopConfig::max_cycles must be -1 (until stopped) or >= 0, got " +
                                std::to_string(c.max_cycles));
  if (c.publish_every < 1)
    throw std::invalid_argument("LoopConfig::publish_every must be >= 1, got " +
                                std::to_string(c.publish_every));
}

std::int64_t period_ns(double rate_hz) noexcept { return std::llround(1e9 / rate_hz); }

const char* to_string(StopReason reason) noexcept {
  switch (reason) {
    case StopReason::stop_requested: return "stop_requested";
    case StopReason::max_cycles: return "max_cycles";
    case StopReason::cycle_returned_false: return "cycle_returned_false";
    case StopReason::sleep_failed: return "sleep_failed";
  }
  return "unknown";
}

namespace detail {

bool enter_realtime(const LoopConfig& config, ThreadReport& report) noexcept {
  if (config.lock_memory) report.memory_status = lock_memory();
  report.realtime_status = set_thread_realtime(config.priority, config.cpu);
  report.realtime = thread_is_realtime();
  if (!config.require_realtime) return true;
  return report.realtime_status.ok() && report.realtime && report.memory_status.ok();
}

void run_on_thread(void (*body)(void*), void* arg) {
  pthread_attr_t attr;
  if (int rc = pthread_attr_init(&attr); rc != 0)
    throw std::system_error(rc, std::generic_category(), "pthread_attr_init");
  if (int rc = pthread_attr_setstacksize(&attr, kLoopStackBytes); rc != 0) {
    pthread_attr_destroy(&attr);
    throw std::system_error(rc, std::generic_category(), "pthread_attr_setstacksize");
  }
  Trampoline trampoline{body, arg};
  pthread_t thread;
  const int rc = pthread_create(&thread, &attr, start_routine, &trampoline);
  pthread_attr_destroy(&attr);
  if (rc != 0) throw std::system_error(rc, std::generic_category(), "pthread_create (loop thread)");
  pthread_setname_np(thread, "knoblab-rt");  // cosmetic (ps/top); failure is harmless
  if (int j = pthread_join(thread, nullptr); j != 0)
    throw std::system_error(j, std::generic_category(), "pthread_join (loop thread)");
}

LoopResult finish(const LoopConfig& config, ThreadReport& report) {
  LoopResult r;
  r.stats = report.stats;
  r.stop_reason = report.stop_reason;
  r.realtime = report.realtime;
  r.realtime_status = report.realtime_status;
  r.memory_status = report.memory_status;
  r.sleep_status = report.sleep_status;

  const Status& sched = report.realtime_status.scheduling;
  const Status& pin = report.realtime_status.affinity;
  if (!sched.ok())
    r.warnings.push_back("no SCHED_FIFO priority " + std::to_string(config.priority) + " (" +
                         status_text(sched) + "): the loop ran with normal scheduling");
  if (!pin.ok())
    r.warnings.push_back("could not pin the loop to CPU " + std::to_string(config.cpu) + " (" +
                         status_text(pin) + ")");
  if (!report.memory_status.ok())
    r.warnings.push_back("could not lock memory (" + status_text(report.memory_status) +
                         "): page faults may add latency");

  if (!report.ran) {
    const Status& failed = !sched.ok() ? sched : !pin.ok() ? pin : report.memory_status;
    const int code = failed.ok() ? EPERM : failed.error;  // FIFO not in effect despite success
    throw std::system_error(code, std::generic_category(),
                            "require_realtime: " + (r.warnings.empty()
                                                        ? std::string("SCHED_FIFO not in effect")
                                                        : r.warnings.front()));
  }
  if (report.error) std::rethrow_exception(report.error);
  return r;
}

}  // namespace detail

}  // namespace knoblab::rt
