// Several connections on one store: readers never wait for a writer, and a
// large import lets other writers in between its short transactions.
#include <gmock/gmock.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "knoblab/store/schema.hpp"
#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
namespace ki = knoblab::interchange;
using ks::test::Child;
using ks::test::checksum;
using ks::test::read_int64;
using ks::test::TempDir;
using ::testing::HasSubstr;

namespace {

ki::Capture synthetic(std::size_t n) { return ks::test::synthetic_capture(n); }

// A store holding one complete capture and one fit.
void populate(const std::filesystem::path& path) {
  auto store = ks::Store::open(path);
  ks::NewCapture info;
  info.knob = "fan";
  const auto id = store.import_capture(synthetic(500), info);
  store.insert_fit(id, "thesis", R"({"M_acc": 2e-5})");
}

// Another process's long transaction: the write lock, held until release().
struct WriteLock {
  ks::sqlite::Connection db;
  explicit WriteLock(const std::filesystem::path& path) : db(ks::sqlite::Connection::open(path)) {
    db.exec("BEGIN IMMEDIATE");
  }
  void release() { db.exec("COMMIT"); }
};

ks::OpenOptions quick(bool read_only = false) {
  ks::OpenOptions o;
  o.busy_timeout_ms = 300;  // the lock below is held far longer
  o.read_only = read_only;
  return o;
}

}  // namespace

TEST(StoreOpen, OpeningAndListingNeedNoWriteLockWhenTheSchemaIsCurrent) {
  TempDir dir;
  const auto path = dir / "k.db";
  populate(path);
  WriteLock lock(path);
  for (const bool read_only : {false, true}) {
    SCOPED_TRACE(read_only ? "read-only" : "read-write");
    auto store = ks::Store::open(path, quick(read_only));
    const auto captures = store.list_captures();
    ASSERT_EQ(captures.size(), 1u);
    EXPECT_EQ(store.load_samples(captures[0].id).size(), 500u);
    EXPECT_EQ(store.list_all_fits().size(), 1u);
  }
  lock.release();
}

TEST(StoreOpen, ADeadWritersCaptureWaitsForRecoveryWhileTheLockIsHeldElsewhere) {
  TempDir dir;
  const auto path = dir / "k.db";
  populate(path);
  const pid_t dead = ::fork();
  ASSERT_GE(dead, 0);
  if (dead == 0) ::_exit(0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
  std::int64_t id = 0;
  {
    auto db = ks::sqlite::Connection::open(path);
    db.prepare(
          "INSERT INTO captures (mode, rate_hz, source, status, writer_pid)"
          " VALUES ('lab', 1000, 'hapticd', 'recording', ?1)")
        .bind_int(1, dead)
        .run();
    id = db.last_insert_rowid();
  }
  WriteLock lock(path);
  {
    // Recovery has something to write but cannot now: the open still works,
    // and the capture is left for a later open.
    auto store = ks::Store::open(path, quick());
    EXPECT_EQ(store.capture_info(id)->status, "recording");
    // A read-only open never even tries.
    auto reader = ks::Store::open(path, quick(true));
    EXPECT_EQ(reader.list_captures().size(), 2u);
  }
  lock.release();
  auto store = ks::Store::open(path, quick());
  const auto info = store.capture_info(id);
  EXPECT_EQ(info->status, "incomplete");
  ASSERT_TRUE(info->end_reason.has_value());
  EXPECT_THAT(*info->end_reason, HasSubstr("pid " + std::to_string(dead)));
}

TEST(StoreOpen, ReadOnlyOpenNeverWrites) {
  TempDir dir;
  const auto path = dir / "k.db";
  // No file: a clear error, and no file made.
  try {
    ks::Store::open(path, quick(true));
    FAIL() << "opened a store that does not exist";
  } catch (const ks::StoreError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no such store"));
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
  }
  EXPECT_FALSE(std::filesystem::exists(path));

  populate(path);  // every connection closed again: no -wal or -shm file left
  std::string before;
  {
    auto db = ks::sqlite::Connection::open(path);
    before = checksum(db);
  }
  auto store = ks::Store::open(path, quick(true));
  EXPECT_EQ(store.list_captures().size(), 1u);
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  const auto error = ks::test::store_error([&] { store.knob_id("volume"); });
  EXPECT_THAT(error, HasSubstr("readonly"));
  EXPECT_EQ(checksum(store.connection()), before);
}

TEST(StoreOpen, ReadOnlyOpenOfAnOlderSchemaUpgradesItFirst) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 4);
    db.exec(
        "INSERT INTO captures (mode, rate_hz, source, status, sample_count)"
        " VALUES ('lab', 1000, 'import', 'incomplete', 0)");
  }
  auto store = ks::Store::open(path, quick(true));
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  const auto captures = store.list_captures();
  ASSERT_EQ(captures.size(), 1u);
  EXPECT_EQ(captures[0].status, "incomplete");
  EXPECT_FALSE(captures[0].end_reason.has_value());  // stored before reasons existed
}

// The import that used to hold the write lock for its whole length (seconds
// for 200 000 rows) now commits in short batches: another connection sees it
// 'recording' part way, and writes in between.
TEST(StoreImport, AnotherWriterCommitsWhileALargeImportIsInProgress) {
  constexpr std::size_t kRows = 200'000;
  TempDir dir;
  const auto path = dir / "k.db";
  { ks::Store::open(path); }
  const ki::Capture big = synthetic(kRows);

  std::atomic<bool> done{false};
  std::int64_t import_id = 0, commits = 0;
  double longest_gap_ms = 0;
  std::string import_error;
  std::thread importer([&] {
    try {
      auto store = ks::Store::open(path);
      ks::ImportOptions options;
      auto last = std::chrono::steady_clock::now();
      options.on_commit = [&](std::int64_t) {
        const auto now = std::chrono::steady_clock::now();
        longest_gap_ms = std::max(longest_gap_ms, std::chrono::duration<double, std::milli>(now - last).count());
        last = now;
        ++commits;
      };
      ks::NewCapture info;
      info.knob = "big";
      import_id = store.import_capture(big, info, options);
    } catch (const std::exception& e) {
      import_error = e.what();
    }
    done = true;
  });

  auto other = ks::Store::open(path);  // e.g. hapticd, recording meanwhile
  bool saw_partial = false;
  int writes_during_import = 0;
  for (int k = 0; !done; ++k) {
    bool partial = false;
    for (const auto& c : other.list_captures())
      if (c.source == "import" && c.status == "recording" && c.sample_count > 0 &&
          c.sample_count < static_cast<std::int64_t>(kRows))
        partial = true;
    if (!partial) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    saw_partial = true;
    // A short write of our own, then check the import had not finished yet.
    ks::NewCapture info;
    info.rate_hz = 1000;
    info.source = "hapticd";
    auto w = other.begin_capture(info);
    for (int i = 0; i < 10; ++i) w.append(ks::test::sample_at(i));
    w.finish();
    const auto imp = other.list_captures().front();
    if (imp.status == "recording") ++writes_during_import;
    // A writer that records commits now and then (hapticd: a batch every
    // 0.2 s), not back to back: sqlite's lock is not fair, so a greedy one
    // would keep the import waiting instead.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  importer.join();
  ASSERT_EQ(import_error, "");
  std::printf("[ figures  ] import of %zu rows: %lld commits, longest commit-to-commit %.1f ms "
              "(waiting for the lock + transaction + %lld ms pause); %d writes of another "
              "connection in between\n",
              kRows, static_cast<long long>(commits), longest_gap_ms,
              static_cast<long long>(ks::ImportOptions{}.pause.count()), writes_during_import);
  EXPECT_TRUE(saw_partial) << "the import was never visible part way";
  EXPECT_GT(writes_during_import, 0);
  EXPECT_GT(commits, 1);
  const auto info = other.capture_info(import_id);
  EXPECT_EQ(info->status, "complete");
  EXPECT_EQ(info->sample_count, static_cast<std::int64_t>(kRows));
  EXPECT_EQ(other.load_samples(import_id).size(), kRows);
  for (const auto& c : other.list_captures()) {
    if (c.id != import_id) {
      EXPECT_EQ(c.status, "complete");
    }
  }
}

TEST(StoreImport, AFailureAfterCommittedBatchesRemovesThePartialCaptureAndItsNewKnob) {
  TempDir dir;
  const auto path = dir / "k.db";
  populate(path);
  auto store = ks::Store::open(path);
  const auto before = checksum(store.connection());
  store.connection().exec(
      "CREATE TEMP TRIGGER fail_mid_import BEFORE INSERT ON samples WHEN NEW.idx = 150"
      " BEGIN SELECT RAISE(ABORT, 'injected failure'); END");
  ks::ImportOptions options;
  options.max_transaction = std::chrono::milliseconds(0);  // a row per transaction
  options.pause = std::chrono::milliseconds(0);
  std::int64_t committed = 0;
  options.on_commit = [&](std::int64_t n) { committed = n; };
  ks::NewCapture info;
  info.knob = "new knob";
  const auto error = ks::test::store_error([&] { store.import_capture(synthetic(300), info, options); });
  EXPECT_THAT(error, HasSubstr("injected failure"));
  EXPECT_EQ(committed, 150);  // really committed before the failure
  store.connection().exec("DROP TRIGGER fail_mid_import");
  EXPECT_EQ(checksum(store.connection()), before);
  // A knob that existed before stays, though the failed import used it.
  info.knob = "fan";
  store.connection().exec(
      "CREATE TEMP TRIGGER fail_again BEFORE INSERT ON samples WHEN NEW.idx = 10"
      " BEGIN SELECT RAISE(ABORT, 'injected failure'); END");
  EXPECT_THROW(store.import_capture(synthetic(300), info, options), ks::StoreError);
  store.connection().exec("DROP TRIGGER fail_again");
  EXPECT_EQ(checksum(store.connection()), before);
}

TEST(StoreImport, AKilledImportIsMarkedIncompleteOnTheNextOpen) {
  TempDir dir;
  const auto path = dir / "k.db";
  { ks::Store::open(path); }  // schema first; no connection open across fork()
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  Child child;
  child.pid = ::fork();
  ASSERT_GE(child.pid, 0);
  if (child.pid == 0) {
    ::close(fds[0]);
    try {
      auto store = ks::Store::open(path);
      ks::ImportOptions options;
      options.max_transaction = std::chrono::milliseconds(1);
      options.pause = std::chrono::milliseconds(1);
      options.on_commit = [&](std::int64_t n) {
        if (::write(fds[1], &n, sizeof n) != sizeof n) ::_exit(3);
      };
      store.import_capture(synthetic(500'000), {}, options);
    } catch (...) {
      ::_exit(2);
    }
    ::_exit(4);  // finished before the kill: the test learns nothing
  }
  ::close(fds[1]);
  std::int64_t reported = 0;
  for (int commits = 0; commits < 5; ++commits)
    ASSERT_TRUE(read_int64(fds[0], reported)) << "child died early";
  {
    auto reader = ks::Store::open(path, quick(true));
    const auto c = reader.list_captures().at(0);
    EXPECT_EQ(c.status, "recording");
    EXPECT_EQ(c.writer_pid, child.pid);
  }
  ASSERT_EQ(::kill(child.pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child.pid, &status, 0), child.pid);
  child.pid = -1;
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  for (std::int64_t n; read_int64(fds[0], n);) reported = n;
  ::close(fds[0]);

  auto store = ks::Store::open(path);
  EXPECT_EQ(store.integrity_check(), "ok");
  const auto c = store.list_captures().at(0);
  EXPECT_EQ(c.status, "incomplete");
  ASSERT_TRUE(c.end_reason.has_value());
  EXPECT_THAT(*c.end_reason, HasSubstr("interrupted"));
  EXPECT_GE(c.sample_count, reported);
  EXPECT_LT(c.sample_count, 500'000);
  EXPECT_EQ(store.load_samples(c.id).size(), static_cast<std::size_t>(c.sample_count));
}
