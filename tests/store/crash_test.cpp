// Crash safety: a writer SIGKILLed mid-stream, and recovery of dead writers.
#include <gmock/gmock.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <bit>
#include <cerrno>

#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::sample_at;
using ks::test::Child;
using ks::test::read_int64;
using ks::test::TempDir;

namespace {

constexpr std::int64_t kBatch = 1000;

// In the child: record "forever", reporting every commit through the pipe.
[[noreturn]] void record_until_killed(const std::filesystem::path& db, int fd) {
  try {
    auto store = ks::Store::open(db);
    ks::WriterOptions options;
    options.batch_size = kBatch;
    options.on_commit = [fd](std::int64_t n) {
      if (::write(fd, &n, sizeof n) != sizeof n) ::_exit(3);
    };
    ks::NewCapture info;
    info.knob = "crash";
    info.rate_hz = 10000;
    info.source = "hapticd";
    info.has_command = true;
    auto w = store.begin_capture(info, options);
    for (std::int64_t i = 0;; ++i) w.append(sample_at(i));
  } catch (...) {
    ::_exit(2);
  }
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

}  // namespace

TEST(StoreCrash, SigkillMidStreamLosesAtMostTheBatchInFlight) {
  TempDir dir;
  const auto path = dir / "k.db";
  { ks::Store::open(path); }  // schema first; no connection open across fork()

  // Several rounds, killing after a different number of batches each time;
  // every earlier capture must survive the later crashes untouched.
  const int kill_after[] = {5, 9, 14};
  for (int round = 0; round < 3; ++round) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    Child child;
    child.pid = ::fork();
    ASSERT_GE(child.pid, 0);
    if (child.pid == 0) {
      ::close(fds[0]);
      record_until_killed(path, fds[1]);
    }
    ::close(fds[1]);

    std::int64_t reported = 0;
    for (int batches = 0; batches < kill_after[round]; ++batches)
      ASSERT_TRUE(read_int64(fds[0], reported)) << "child died early";
    ::usleep(static_cast<useconds_t>(round * 700));  // land at different points of a batch
    ASSERT_EQ(::kill(child.pid, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child.pid, &status, 0), child.pid);  // reaped: a zombie counts as alive
    child.pid = -1;
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
    // Reports that made it into the pipe before the kill were committed too.
    for (std::int64_t n; read_int64(fds[0], n);) reported = n;
    ::close(fds[0]);

    auto store = ks::Store::open(path);
    EXPECT_EQ(store.integrity_check(), "ok");
    const auto captures = store.list_captures();
    ASSERT_EQ(captures.size(), static_cast<std::size_t>(round + 1));
    for (const auto& info : captures) {
      SCOPED_TRACE("capture " + std::to_string(info.id));
      EXPECT_EQ(info.status, "incomplete");
      EXPECT_TRUE(info.finished_at.has_value());
      const auto rows = store.connection().query_int(
          "SELECT count(*) FROM samples WHERE capture_id = " + std::to_string(info.id));
      EXPECT_EQ(info.sample_count, rows);
      EXPECT_EQ(rows % kBatch, 0) << "a partial batch was committed";
      const auto c = store.load_samples(info.id);
      ASSERT_EQ(c.size(), static_cast<std::size_t>(rows));
      for (std::size_t i = 0; i < c.size(); ++i) {
        const auto s = sample_at(static_cast<std::int64_t>(i));
        ASSERT_TRUE(same_bits(c.t[i], s.t) && same_bits(c.theta[i], s.theta) &&
                    same_bits(c.omega[i], s.omega) && same_bits(c.alpha[i], s.alpha) &&
                    same_bits(c.torque[i], s.torque) && same_bits(c.command[i], s.command))
            << "sample " << i;
      }
    }
    // The capture just killed: everything reported is there, and at most the
    // one batch committed between the last report and the kill is extra.
    const auto& last = captures.back();
    EXPECT_GE(last.sample_count, reported);
    EXPECT_LE(last.sample_count, reported + kBatch);
  }
}

TEST(StoreCrash, LiveWriterIsLeftAlone) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  ks::NewCapture info;
  info.rate_hz = 1000;
  info.source = "hapticd";
  auto w = store.begin_capture(info);
  for (int i = 0; i < 10; ++i) w.append(sample_at(i));
  w.flush();
  // Another process (here: connection) opening the store meanwhile.
  auto other = ks::Store::open(dir / "k.db");
  EXPECT_TRUE(other.recover_interrupted().empty());
  EXPECT_EQ(other.capture_info(w.capture_id())->status, "recording");
  w.finish();
  EXPECT_EQ(other.capture_info(w.capture_id())->status, "complete");
}

TEST(StoreCrash, DeadOrOtherBootWritersAreMarkedIncomplete) {
  TempDir dir;
  const auto path = dir / "k.db";
  // A pid that surely does not exist any more: a child we reaped.
  const pid_t dead = ::fork();
  ASSERT_GE(dead, 0);
  if (dead == 0) ::_exit(0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);

  std::int64_t dead_id = 0, reboot_id = 0, live_id = 0;
  {
    auto store = ks::Store::open(path);
    auto& db = store.connection();
    const auto insert = [&](std::int64_t pid, const char* boot) {
      auto st = db.prepare(
          "INSERT INTO captures (mode, rate_hz, source, status, writer_pid, writer_boot)"
          " VALUES ('lab', 1000, 'hapticd', 'recording', ?1, ?2)");
      st.bind_int(1, pid);
      if (boot) st.bind_text(2, boot);
      st.run();
      const auto id = db.last_insert_rowid();
      for (int i = 0; i < 7; ++i)
        db.exec("INSERT INTO samples VALUES (" + std::to_string(id) + ", " + std::to_string(i) +
                ", " + std::to_string(i) + ", 0, 0, 0, 0, NULL, 0)");
      return id;
    };
    dead_id = insert(dead, nullptr);
    reboot_id = insert(::getpid(), "00000000-0000-0000-0000-000000000000");  // alive pid, old boot
    live_id = insert(::getpid(), nullptr);
  }
  auto store = ks::Store::open(path);
  for (auto id : {dead_id, reboot_id}) {
    const auto info = store.capture_info(id);
    EXPECT_EQ(info->status, "incomplete") << id;
    EXPECT_EQ(info->sample_count, 7) << id;
  }
  EXPECT_EQ(store.capture_info(live_id)->status, "recording");
}
