// POSIX implementation of the OS seam. Under Xenomai this very file is
// compiled with the Cobalt flags; the calls below then reach Cobalt.
#include "knoblab/rt/os.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <cerrno>
#include <cstring>

namespace knoblab::rt {

namespace {
constexpr std::int64_t kNsPerSec = 1'000'000'000;
constexpr std::size_t kPageBytes = 4096;

// Writes through a volatile pointer cannot be optimised away, so every page
// of this frame really is touched (and, after mlockall, stays resident).
[[gnu::noinline]] void prefault_stack() noexcept {
  unsigned char frame[kPrefaultStackBytes];
  volatile unsigned char* p = frame;
  for (std::size_t i = 0; i < sizeof frame; i += kPageBytes) p[i] = 0;
}
}  // namespace

std::string Status::message() const {
  if (ok()) return "ok";
  return std::string(call) + ": " + std::strerror(error);
}

const char* backend_name() noexcept {
#if defined(KNOBLAB_RT_BACKEND_XENOMAI)
  return "xenomai";
#else
  return "posix";
#endif
}

Status lock_memory() noexcept {
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) return {errno, "mlockall"};
  prefault_stack();
  return {};
}

RealtimeStatus set_thread_realtime(int priority, int cpu) noexcept {
  RealtimeStatus s;
  sched_param param{};
  param.sched_priority = priority;
  if (int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param); rc != 0)
    s.scheduling = {rc, "pthread_setschedparam(SCHED_FIFO)"};
  if (cpu >= 0) {
    if (cpu >= CPU_SETSIZE) {
      s.affinity = {EINVAL, "pthread_setaffinity_np"};
    } else {
      cpu_set_t set;
      CPU_ZERO(&set);
      CPU_SET(static_cast<std::size_t>(cpu), &set);
      if (int rc = pthread_setaffinity_np(pthread_self(), sizeof set, &set); rc != 0)
        s.affinity = {rc, "pthread_setaffinity_np"};
    }
  }
  return s;
}

bool thread_is_realtime() noexcept {
  int policy = 0;
  sched_param param{};
  return pthread_getschedparam(pthread_self(), &policy, &param) == 0 && policy == SCHED_FIFO;
}

std::int64_t now() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerSec + ts.tv_nsec;
}

Status sleep_until(std::int64_t deadline_ns) noexcept {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline_ns / kNsPerSec);
  ts.tv_nsec = static_cast<long>(deadline_ns % kNsPerSec);
  int rc;
  // Absolute time: a restart after a signal keeps the same deadline.
  while ((rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr)) == EINTR) {
  }
  if (rc != 0) return {rc, "clock_nanosleep"};
  return {};
}

}  // namespace knoblab::rt
