// The ring across processes, as the daemon and the UI use it: the reader
// is a forked child that finds the ring by name.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <vector>

#include "knoblab/control/telemetry_reader.hpp"
#include "knoblab/control/telemetry_writer.hpp"
#include "telemetry_support.hpp"

namespace knoblab::control::test {
namespace {

struct ChildReport {
  std::uint64_t read = 0, lost = 0, torn = 0, gaps = 0;
  int error = 0;
};

// Runs in the child: no gtest, just a report down the pipe.
ChildReport read_in_child(const std::string& name, std::uint64_t records, std::uint32_t decimation, int ready_fd) {
  ChildReport rep;
  try {
    TelemetryReader r(name, TelemetryReader::Start::oldest);
    const char ok = 'r';
    if (::write(ready_fd, &ok, 1) != 1) rep.error = 2;
    std::vector<TelemetryRecord> out(16);
    std::uint64_t expected = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (r.cursor() < records && std::chrono::steady_clock::now() < deadline) {
      const auto res = r.read(out);
      if (res.first_sequence != expected + res.lost) ++rep.gaps;
      expected = res.first_sequence + res.count;
      rep.read += res.count;
      rep.lost += res.lost;
      for (std::size_t k = 0; k < res.count; ++k)
        if (!consistent(out[k], decimation)) ++rep.torn;
    }
  } catch (...) {
    rep.error = 1;
  }
  return rep;
}

TEST(TelemetryProcesses, ForkedReaderSeesUntornRecordsAndCountsLosses) {
  constexpr std::uint32_t kDecimation = 1;
  constexpr std::uint64_t kSamples = 2'000'000;
  TelemetryConfig cfg;
  cfg.shm_name = unique_shm_name("fork");
  cfg.capacity = 256;
  cfg.decimation = kDecimation;
  TelemetryWriter w(cfg);

  int report_pipe[2], ready_pipe[2];
  ASSERT_EQ(::pipe(report_pipe), 0);
  ASSERT_EQ(::pipe(ready_pipe), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(report_pipe[0]);
    ::close(ready_pipe[0]);
    const ChildReport rep = read_in_child(cfg.shm_name, kSamples / kDecimation, kDecimation, ready_pipe[1]);
    const bool sent = ::write(report_pipe[1], &rep, sizeof rep) == static_cast<ssize_t>(sizeof rep);
    ::_exit(sent ? 0 : 3);
  }
  ::close(report_pipe[1]);
  ::close(ready_pipe[1]);
  char ready = 0;
  ASSERT_EQ(::read(ready_pipe[0], &ready, 1), 1) << "child could not open the ring";

  for (std::uint64_t i = 0; i < kSamples; ++i) w.push(counter_sample(i));

  ChildReport rep;
  const ssize_t n = ::read(report_pipe[0], &rep, sizeof rep);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ::close(report_pipe[0]);
  ::close(ready_pipe[0]);
  ASSERT_EQ(n, static_cast<ssize_t>(sizeof rep));
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(rep.error, 0);
  EXPECT_EQ(rep.torn, 0u);
  EXPECT_EQ(rep.gaps, 0u);
  EXPECT_EQ(rep.read + rep.lost, kSamples / kDecimation);
  EXPECT_GT(rep.read, 0u);
  std::printf("[          ] child read %llu, lost %llu\n", static_cast<unsigned long long>(rep.read),
              static_cast<unsigned long long>(rep.lost));
}

}  // namespace
}  // namespace knoblab::control::test
