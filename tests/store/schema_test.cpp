// Opening: pragmas, migrations, refusal of newer databases.
#include <gmock/gmock.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <vector>

#include "knoblab/store/schema.hpp"
#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::TempDir;
using ::testing::HasSubstr;

TEST(StoreSchema, FreshDatabaseGetsLatestVersionAndPragmas) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  EXPECT_GE(ks::latest_schema_version(), 6);
  auto& db = store.connection();
  EXPECT_EQ(db.query_text("PRAGMA journal_mode"), "wal");
  EXPECT_EQ(db.query_int("PRAGMA synchronous"), 2);  // FULL
  EXPECT_EQ(db.query_int("PRAGMA foreign_keys"), 1);
  EXPECT_EQ(db.query_int("PRAGMA busy_timeout"), 5000);
  EXPECT_EQ(db.query_int("SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND name IN"
                         " ('knobs', 'captures', 'samples', 'biometrics', 'fits', 'fit_files',"
                         " 'discrepancies')"),
            7);
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST(StoreSchema, ReopeningIsIdempotent) {
  TempDir dir;
  std::string before;
  {
    auto store = ks::Store::open(dir / "k.db");
    store.knob_id("fan");
    before = ks::test::checksum(store.connection());
  }
  for (int i = 0; i < 3; ++i) {
    auto store = ks::Store::open(dir / "k.db");
    EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
    EXPECT_EQ(ks::test::checksum(store.connection()), before);
  }
}

TEST(StoreSchema, NewerDatabaseIsRefusedUntouched) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    db.exec("CREATE TABLE future (x); PRAGMA user_version = " +
            std::to_string(ks::latest_schema_version() + 1));
  }
  try {
    ks::Store::open(path);
    FAIL() << "opened a newer database";
  } catch (const ks::StoreError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is newer than this knoblab"));
    EXPECT_THAT(e.what(), HasSubstr(path.string()));
  }
  auto db = ks::sqlite::Connection::open(path);
  EXPECT_EQ(db.query_text("PRAGMA journal_mode"), "delete");  // not even switched to WAL
  EXPECT_EQ(ks::schema_version(db), ks::latest_schema_version() + 1);
}

TEST(StoreSchema, UpgradesAnOldDatabaseKeepingItsData) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 1);
    EXPECT_EQ(ks::schema_version(db), 1);
    db.exec("INSERT INTO knobs (name) VALUES ('old knob')");
  }
  auto store = ks::Store::open(path);
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  ASSERT_EQ(store.list_knobs().size(), 1u);
  EXPECT_EQ(store.list_knobs()[0].name, "old knob");
  EXPECT_EQ(store.connection().query_int(
                "SELECT count(*) FROM sqlite_schema WHERE name IN"
                " ('fits_by_capture', 'discrepancies_by_capture')"),
            2);
}

TEST(StoreSchema, FailingStepRollsBackToThePreviousVersion) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 1);
    // Step 2 creates index captures_by_knob, then trips over this name.
    db.exec("CREATE TABLE captures_by_status (x)");
  }
  try {
    ks::Store::open(path);
    FAIL() << "migration should have failed";
  } catch (const ks::StoreError& e) {
    EXPECT_THAT(e.what(), HasSubstr("migration to version 2 failed"));
  }
  auto db = ks::sqlite::Connection::open(path);
  EXPECT_EQ(ks::schema_version(db), 1);
  EXPECT_EQ(db.query_int("SELECT count(*) FROM sqlite_schema WHERE name = 'captures_by_knob'"), 0);
}

TEST(StoreSchema, ConcurrentFirstOpensAllSucceed) {
  TempDir dir;
  const auto path = dir / "k.db";
  std::vector<pid_t> children;
  for (int i = 0; i < 6; ++i) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      int rc = 0;
      try {
        auto store = ks::Store::open(path);
        rc = store.schema_version() == ks::latest_schema_version() ? 0 : 2;
      } catch (const std::exception& e) {
        std::fprintf(stderr, "child %d: %s\n", i, e.what());
        rc = 1;
      }
      ::_exit(rc);
    }
    children.push_back(pid);
  }
  for (pid_t pid : children) {
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status;
  }
}

TEST(StoreSchema, NotADatabaseIsAClearError) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    std::ofstream out(path);
    out << std::string(4096, 'x');
  }
  try {
    ks::Store::open(path);
    FAIL() << "opened garbage";
  } catch (const ks::StoreError& e) {
    EXPECT_THAT(e.what(), HasSubstr("not a database"));
  }
}
