// Acceptance: SIGKILL a capture in progress; what was committed survives,
// the database is intact, and the capture is marked incomplete.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <thread>

#include "knoblab/store/store.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

TEST(Crash, SigkillMidCaptureKeepsEveryCommittedBatch) {
  ScratchDir dir;
  const auto db_path = dir / "lab.sqlite";
  const pid_t pid = spawn_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "60", "--rate",
                                   "10000", "--db", db_path.string()});
  // Wait until a few batches are committed, reading as a second process would.
  std::int64_t seen = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (seen < 10000 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (!std::filesystem::exists(db_path)) continue;
    try {
      store::Store s = store::Store::open(db_path);
      if (auto info = s.capture_info(1)) {
        ASSERT_EQ(info->status, "recording");  // the writer is alive: left alone
        seen = info->sample_count;
      }
    } catch (const std::exception&) {
      // The writer may be creating the schema right now.
    }
  }
  ASSERT_GE(seen, 10000) << "the capture never got going";
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));

  store::Store s = store::Store::open(db_path);
  EXPECT_EQ(s.integrity_check(), "ok");
  const auto info = s.capture_info(1);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, "incomplete");
  EXPECT_GE(info->sample_count, seen);
  EXPECT_LT(info->sample_count, 600000) << "the kill came too late to test anything";
  EXPECT_EQ(info->sample_count % 2000, 0) << "only whole batches are committed";
  const interchange::Capture c = s.load_samples(1);
  ASSERT_EQ(static_cast<std::int64_t>(c.size()), info->sample_count);
  for (std::size_t i = 0; i < c.size(); ++i) ASSERT_EQ(c.t[i], static_cast<double>(i) * (1.0 / 10000.0));
}

}  // namespace
}  // namespace knoblab::test
