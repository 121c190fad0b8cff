// The OS seam: clock, absolute sleep, realtime scheduling, failure reports.
#include <gtest/gtest.h>
#include <sched.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

#include "knoblab/rt/os.hpp"

using namespace knoblab::rt;

TEST(Os, BackendIsPosixOnTheseMachines) { EXPECT_STREQ(backend_name(), "posix"); }

TEST(Os, ClockIsMonotonicNanoseconds) {
  const std::int64_t a = now();
  const std::int64_t b = now();
  EXPECT_GT(a, 0);
  EXPECT_GE(b, a);
}

TEST(Os, SleepUntilNeverWakesEarly) {
  const std::int64_t deadline = now() + 2'000'000;  // 2 ms ahead
  const Status s = sleep_until(deadline);
  const std::int64_t woke = now();
  EXPECT_TRUE(s.ok()) << s.message();
  EXPECT_GE(woke, deadline);
  std::printf("[ figures  ] woke %lld ns after the deadline\n", static_cast<long long>(woke - deadline));
}

TEST(Os, SleepUntilAPastDeadlineReturnsAtOnce) {
  EXPECT_TRUE(sleep_until(now() - 1'000'000).ok());
}

TEST(Os, SleepUntilReportsAnInvalidTime) {
  const Status s = sleep_until(-1);  // negative tv_nsec: EINVAL, not a silent return
  EXPECT_EQ(s.error, EINVAL);
  EXPECT_STREQ(s.call, "clock_nanosleep");
  EXPECT_NE(s.message().find("clock_nanosleep"), std::string::npos);
}

TEST(Os, RealtimeStatusMatchesTheScheduler) {
  RealtimeStatus status;
  int policy = -1;
  std::thread t([&] {
    status = set_thread_realtime(10, -1);
    policy = sched_getscheduler(0);  // 0: the calling thread
  });
  t.join();
  EXPECT_TRUE(status.affinity.ok());  // no pinning asked
  EXPECT_EQ(status.realtime(), policy == SCHED_FIFO) << status.scheduling.message();
  std::printf("[ figures  ] SCHED_FIFO %s\n", status.realtime() ? "obtained" : status.scheduling.message().c_str());
}

TEST(Os, InvalidPriorityIsReportedNotIgnored) {
  RealtimeStatus status;
  std::thread t([&] { status = set_thread_realtime(1000, -1); });
  t.join();
  EXPECT_FALSE(status.realtime());
  EXPECT_EQ(status.scheduling.error, EINVAL);
}

TEST(Os, PinningToAMissingCpuIsReported) {
  RealtimeStatus status;
  bool pinned_elsewhere = false;
  std::thread t([&] {
    status = set_thread_realtime(10, CPU_SETSIZE - 1);  // no such CPU here
    cpu_set_t set;
    CPU_ZERO(&set);
    pinned_elsewhere = sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) == 1;
  });
  t.join();
  EXPECT_FALSE(status.affinity.ok());
  EXPECT_STREQ(status.affinity.call, "pthread_setaffinity_np");
  EXPECT_FALSE(pinned_elsewhere && std::thread::hardware_concurrency() > 1);
  EXPECT_FALSE(status.ok());
}

TEST(Os, PinningToCpuZeroWorks) {
  RealtimeStatus status;
  int cpu = -1;
  std::thread t([&] {
    status = set_thread_realtime(10, 0);
    cpu = sched_getcpu();
  });
  t.join();
  ASSERT_TRUE(status.affinity.ok()) << status.affinity.message();
  EXPECT_EQ(cpu, 0);
}

TEST(Os, LockMemoryReportsItsOutcome) {
  const Status s = lock_memory();
  if (!s.ok()) {
    EXPECT_STREQ(s.call, "mlockall");
    EXPECT_NE(s.error, 0);
  } else {
    std::ifstream in("/proc/self/status");
    long locked_kb = -1;
    for (std::string line; std::getline(in, line);)
      if (line.rfind("VmLck:", 0) == 0) locked_kb = std::stol(line.substr(6));
    EXPECT_GT(locked_kb, 0) << "mlockall reported success but nothing is locked";
  }
  std::printf("[ figures  ] lock_memory: %s\n", s.message().c_str());
}
