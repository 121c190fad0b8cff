// The OS seam of the realtime loop (in the spirit of LinuxCNC's rtapi): the
// handful of calls a periodic thread needs, nothing more. One POSIX source
// serves both backends, chosen at build time by KNOBLAB_RT_BACKEND:
//   posix    plain Linux or PREEMPT_RT (the default, and what these machines build);
//   xenomai  Xenomai 3 Cobalt: the same source compiled and linked with
//            `xeno-config --posix --cflags/--ldflags`, so pthread_create,
//            clock_nanosleep, pthread_setschedparam … resolve to the Cobalt
//            wrappers. That variant is built by the Yocto layer, not here.
// Every call reports failure; none is silently ignored.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace knoblab::rt {

// Outcome of one OS call: 0 or the errno it failed with, and which call.
// Trivially copyable and allocation-free, so the loop may carry it around.
struct Status {
  int error = 0;
  const char* call = "";
  bool ok() const noexcept { return error == 0; }
  std::string message() const;  // "mlockall: Operation not permitted"; not for the loop
};

// Scheduling and pinning fail independently, so both are reported.
struct RealtimeStatus {
  Status scheduling;  // pthread_setschedparam(SCHED_FIFO)
  Status affinity;    // pthread_setaffinity_np; ok when no pinning was asked
  bool realtime() const noexcept { return scheduling.ok(); }
  bool ok() const noexcept { return scheduling.ok() && affinity.ok(); }
};

// Which backend this library was built for: "posix" or "xenomai".
const char* backend_name() noexcept;

// mlockall(MCL_CURRENT | MCL_FUTURE), then touch kPrefaultStackBytes of the
// calling thread's stack so its first deep call does not page-fault.
inline constexpr std::size_t kPrefaultStackBytes = 256 * 1024;
Status lock_memory() noexcept;

// Make the calling thread SCHED_FIFO at `priority` (1..99) and, when cpu >= 0,
// pin it to that CPU. Both are attempted; each outcome is reported.
RealtimeStatus set_thread_realtime(int priority, int cpu) noexcept;

// True when the calling thread currently runs under SCHED_FIFO.
bool thread_is_realtime() noexcept;

// CLOCK_MONOTONIC in nanoseconds.
std::int64_t now() noexcept;

// Sleep until the absolute CLOCK_MONOTONIC time `deadline_ns`
// (clock_nanosleep TIMER_ABSTIME), resuming after signals (EINTR).
// Returns at once when the deadline has passed.
Status sleep_until(std::int64_t deadline_ns) noexcept;

}  // namespace knoblab::rt
