// Fits with their report files: bit-exact round trips, one transaction per
// fit, cascades, the migration that added fit_files, and a SIGKILL mid-insert.
#include <gmock/gmock.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <string>
#include <vector>

#include "knoblab/store/schema.hpp"
#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::store_error;
using ks::test::TempDir;
using ::testing::HasSubstr;

namespace {

std::vector<std::uint8_t> bytes_of(std::string_view text) { return {text.begin(), text.end()}; }

// Every byte value, zeros included, after a PNG signature and IHDR length.
std::vector<std::uint8_t> binary_blob() {
  std::vector<std::uint8_t> b = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13};
  for (int round = 0; round < 3; ++round)
    for (int v = 0; v < 256; ++v) b.push_back(static_cast<std::uint8_t>(v));
  b.insert(b.end(), 17, 0);  // and a run of zeros at the very end
  return b;
}

// Deterministic content of file k of fit i, `size` bytes, with zeros.
std::vector<std::uint8_t> pattern(std::int64_t i, int k, std::size_t size) {
  std::vector<std::uint8_t> b(size);
  for (std::size_t j = 0; j < size; ++j)
    b[j] = static_cast<std::uint8_t>((j * 31u + static_cast<std::size_t>(i) * 7u +
                                      static_cast<std::size_t>(k)) &
                                     0xffu);
  return b;
}

std::vector<ks::FitFile> report_files() {
  return {
      {"fit.json", bytes_of("{\n  \"model\": \"thesis6\"\n}\n")},
      {"torque_vs_theta.png", binary_blob()},
      {"empty.svg", {}},
      {"big.bin", pattern(1, 0, 3u << 20)},  // spans many pages and overflow chains
      {"render_model.json", bytes_of(R"({"model":"render4"})")},
  };
}

std::int64_t finished_capture(ks::Store& store, const std::string& knob = "fan") {
  ks::NewCapture info;
  info.knob = knob;
  info.rate_hz = 1000;
  info.source = "simulate";
  auto w = store.begin_capture(info);
  for (int i = 0; i < 5; ++i) w.append(ks::test::sample_at(i));
  w.finish();
  return w.capture_id();
}

std::int64_t count(ks::Store& store, const std::string& table) {
  return store.connection().query_int("SELECT count(*) FROM " + table);
}

}  // namespace

TEST(StoreFitFiles, FilesComeBackBitExact) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  const auto files = report_files();
  const auto id = store.insert_fit(capture, "thesis6", R"({"model":"thesis6"})",
                                   R"({"rmse_Nm": 0.001})", files);

  const auto info = store.fit_info(id);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->id, id);
  EXPECT_EQ(info->capture_id, capture);
  EXPECT_EQ(info->model, "thesis6");
  EXPECT_EQ(info->params, R"({"model":"thesis6"})");
  EXPECT_EQ(info->result, R"({"rmse_Nm": 0.001})");
  EXPECT_FALSE(info->created_at.empty());

  // Listed by name (byte order), with sizes.
  const auto listed = store.list_fit_files(id);
  ASSERT_EQ(listed.size(), files.size());
  const std::vector<std::string> names = {"big.bin", "empty.svg", "fit.json", "render_model.json",
                                          "torque_vs_theta.png"};
  for (std::size_t k = 0; k < names.size(); ++k) {
    EXPECT_EQ(listed[k].name, names[k]);
    const auto& original = *std::find_if(files.begin(), files.end(),
                                         [&](const ks::FitFile& f) { return f.name == names[k]; });
    EXPECT_EQ(listed[k].size, static_cast<std::int64_t>(original.bytes.size())) << names[k];
  }

  for (const auto& f : files) EXPECT_EQ(store.load_fit_file(id, f.name), f.bytes) << f.name;
  const auto all = store.load_fit_files(id);
  ASSERT_EQ(all.size(), files.size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    EXPECT_EQ(all[k].name, names[k]);
    EXPECT_EQ(all[k].bytes, store.load_fit_file(id, names[k])) << names[k];
  }

  // Stored as BLOBs, the empty one too (not NULL, not text).
  EXPECT_EQ(store.connection().query_int(
                "SELECT count(*) FROM fit_files WHERE typeof(bytes) = 'blob'"),
            static_cast<std::int64_t>(files.size()));
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST(StoreFitFiles, FitsWithoutFilesAndListing) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto a = finished_capture(store, "fan");
  const auto b = finished_capture(store, "volume");
  const auto f1 = store.insert_fit(a, "thesis6", "{}");  // the four-argument form
  const auto f2 = store.insert_fit(b, "render4", "{}", "{}", report_files());
  const auto f3 = store.insert_fit(a, "render4", "{}", R"({"fit_percent": 97})");

  EXPECT_TRUE(store.list_fit_files(f1).empty());
  EXPECT_TRUE(store.load_fit_files(f1).empty());
  EXPECT_EQ(store.list_fit_files(f2).size(), report_files().size());

  const auto all = store.list_all_fits();
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].id, f1);
  EXPECT_EQ(all[1].id, f2);
  EXPECT_EQ(all[1].capture_id, b);
  EXPECT_EQ(all[2].id, f3);
  EXPECT_EQ(all[2].result, R"({"fit_percent": 97})");
  const auto of_a = store.list_fits(a);
  ASSERT_EQ(of_a.size(), 2u);
  EXPECT_EQ(of_a[0].id, f1);
  EXPECT_EQ(of_a[1].id, f3);
}

TEST(StoreFitFiles, UnknownIdsAndNames) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  const auto id = store.insert_fit(capture, "thesis6", "{}", "{}", report_files());
  const auto unknown = id + 100;

  EXPECT_FALSE(store.fit_info(unknown));
  EXPECT_FALSE(store.fit_info(0));
  EXPECT_TRUE(store.list_fit_files(unknown).empty());
  EXPECT_THAT(store_error([&] { store.load_fit_file(unknown, "fit.json"); }),
              HasSubstr("no fit with id " + std::to_string(unknown)));
  EXPECT_THAT(store_error([&] { store.load_fit_files(unknown); }),
              HasSubstr("no fit with id " + std::to_string(unknown)));
  EXPECT_THAT(store_error([&] { store.load_fit_file(id, "nope.png"); }),
              HasSubstr("fit " + std::to_string(id) + " has no file 'nope.png'"));
  // Names are exact: no case folding, no prefix match.
  EXPECT_THAT(store_error([&] { store.load_fit_file(id, "FIT.JSON"); }), HasSubstr("has no file"));
  EXPECT_THAT(store_error([&] { store.load_fit_file(id, "fit"); }), HasSubstr("has no file"));
  EXPECT_FALSE(store.connection().in_transaction());  // the read snapshot was ended
}

TEST(StoreFitFiles, AFailingFileLeavesNoFitBehind) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  store.insert_fit(capture, "thesis6", "{}", "{}",
                   std::vector<ks::FitFile>{{"kept.json", bytes_of("{}")}});
  const std::string before = ks::test::checksum(store.connection());

  auto files = report_files();
  files.push_back({"fit.json", bytes_of("a second fit.json")});  // duplicate, last
  const std::string dup = store_error([&] { store.insert_fit(capture, "thesis6", "{}", "{}", files); });
  EXPECT_THAT(dup, HasSubstr("UNIQUE constraint failed"));
  EXPECT_THAT(dup, HasSubstr("fit file 'fit.json'"));

  for (const std::string& bad :
       {std::string(), std::string("plots/a.png"), std::string("../a.png"), std::string("/etc/x"),
        std::string("."), std::string(".."), std::string("a\0b.png", 7)}) {
    SCOPED_TRACE("name '" + bad + "'");
    std::vector<ks::FitFile> with_bad = {{"ok.png", binary_blob()}, {bad, binary_blob()}};
    EXPECT_FALSE(store_error([&] { store.insert_fit(capture, "thesis6", "{}", "{}", with_bad); })
                     .empty());
  }
  // A bad fit row with good files: the files do not land either.
  EXPECT_THAT(store_error([&] { store.insert_fit(capture, "thesis6", "{}", "not json", files); }),
              HasSubstr("CHECK constraint failed"));
  EXPECT_THAT(store_error([&] { store.insert_fit(capture + 1, "thesis6", "{}", "{}", files); }),
              HasSubstr("FOREIGN KEY constraint failed"));

  EXPECT_EQ(ks::test::checksum(store.connection()), before);
  EXPECT_EQ(count(store, "fits"), 1);
  EXPECT_EQ(count(store, "fit_files"), 1);
  EXPECT_FALSE(store.connection().in_transaction());
  // The store is fine afterwards; names like these are ordinary.
  const auto id = store.insert_fit(
      capture, "thesis6", "{}", "{}",
      std::vector<ks::FitFile>{{"..a", {}}, {".hidden", {1}}, {"a b (2).svg", {0}}});
  EXPECT_EQ(store.list_fit_files(id).size(), 3u);
}

TEST(StoreFitFiles, DeletingACaptureDeletesItsFitsAndTheirFiles) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto a = finished_capture(store, "fan");
  const auto b = finished_capture(store, "volume");
  const auto fa1 = store.insert_fit(a, "thesis6", "{}", "{}", report_files());
  const auto fa2 = store.insert_fit(a, "render4", "{}", "{}",
                                    std::vector<ks::FitFile>{{"fit.json", bytes_of("{}")}});
  const auto fb = store.insert_fit(b, "thesis6", "{}", "{}", report_files());
  const auto per_fit = static_cast<std::int64_t>(report_files().size());
  ASSERT_EQ(count(store, "fit_files"), 2 * per_fit + 1);

  store.delete_capture(a);
  EXPECT_FALSE(store.fit_info(fa1));
  EXPECT_FALSE(store.fit_info(fa2));
  EXPECT_TRUE(store.list_fit_files(fa1).empty());
  EXPECT_EQ(count(store, "fits"), 1);
  EXPECT_EQ(count(store, "fit_files"), per_fit);
  // The other capture's fit is untouched.
  for (const auto& f : report_files()) EXPECT_EQ(store.load_fit_file(fb, f.name), f.bytes);

  // A fit row deleted on its own takes its files along too.
  store.connection().exec("DELETE FROM fits WHERE id = " + std::to_string(fb));
  EXPECT_EQ(count(store, "fit_files"), 0);
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST(StoreFitFiles, FileRowsNeedAnExistingFit) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  EXPECT_THAT(store_error([&] {
                store.connection().exec(
                    "INSERT INTO fit_files (fit_id, name, bytes) VALUES (42, 'a', x'00')");
              }),
              HasSubstr("FOREIGN KEY constraint failed"));
  const auto id = store.insert_fit(finished_capture(store), "thesis6", "{}");
  EXPECT_THAT(store_error([&] {
                store.connection().exec("INSERT INTO fit_files (fit_id, name, bytes) VALUES (" +
                                        std::to_string(id) + ", 'a.txt', 'text, not a blob')");
              }),
              HasSubstr("CHECK constraint failed"));
}

// ---- migration ------------------------------------------------------------

TEST(StoreFitFiles, Version3DatabaseIsUpgradedKeepingItsFits) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    // A database as knoblab wrote it before fit files existed.
    auto db = ks::sqlite::Connection::open(path);
    db.exec("PRAGMA foreign_keys = ON");
    ks::migrate(db, 3);
    ASSERT_EQ(ks::schema_version(db), 3);
    db.exec(R"sql(
INSERT INTO knobs (id, name) VALUES (1, 'fan');
INSERT INTO captures (id, knob_id, mode, rate_hz, source, status, sample_count)
  VALUES (1, 1, 'lab', 1000, 'import', 'complete', 2);
INSERT INTO samples VALUES (1, 0, 0.0, 0.1, 0.2, 0.3, 0.4, NULL, 0);
INSERT INTO samples VALUES (1, 1, 0.001, 0.5, 0.6, 0.7, 0.8, NULL, 1);
INSERT INTO fits (id, capture_id, model, params, result, created_at)
  VALUES (7, 1, 'thesis6', '{"M_acc":1e-5}', '{"rmse_Nm":0.002}', '2024-05-01T10:00:00.000Z');
)sql");
    EXPECT_EQ(db.query_int("SELECT count(*) FROM sqlite_schema WHERE name = 'fit_files'"), 0);
  }

  auto store = ks::Store::open(path);
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  EXPECT_GE(store.schema_version(), 4);
  EXPECT_EQ(store.integrity_check(), "ok");
  EXPECT_FALSE(store.connection().prepare("PRAGMA foreign_key_check").step());  // no violations
  const auto old_fit = store.fit_info(7);
  ASSERT_TRUE(old_fit);
  EXPECT_EQ(old_fit->capture_id, 1);
  EXPECT_EQ(old_fit->model, "thesis6");
  EXPECT_EQ(old_fit->params, R"({"M_acc":1e-5})");
  EXPECT_EQ(old_fit->result, R"({"rmse_Nm":0.002})");
  EXPECT_EQ(old_fit->created_at, "2024-05-01T10:00:00.000Z");
  EXPECT_TRUE(store.list_fit_files(7).empty());
  EXPECT_EQ(store.load_samples(1).size(), 2u);
  EXPECT_EQ(store.list_knobs().at(0).name, "fan");

  // The upgraded database takes fits with files, and cascades through them.
  const auto files = report_files();
  const auto id = store.insert_fit(1, "render4", "{}", "{}", files);
  EXPECT_GT(id, 7);
  EXPECT_EQ(store.load_fit_file(id, "torque_vs_theta.png"), binary_blob());
  store.delete_capture(1);
  EXPECT_EQ(count(store, "fits"), 0);
  EXPECT_EQ(count(store, "fit_files"), 0);
}

TEST(StoreFitFiles, FailedMigrationToVersion4LeavesVersion3) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 3);
    db.exec("CREATE TABLE fit_files (x)");  // in the way of step 4
  }
  EXPECT_THAT(store_error([&] { ks::Store::open(path); }),
              HasSubstr("migration to version 4 failed"));
  auto db = ks::sqlite::Connection::open(path);
  EXPECT_EQ(ks::schema_version(db), 3);
}

// ---- crash safety ---------------------------------------------------------

namespace {

constexpr int kFilesPerFit = 4;
constexpr std::size_t kFileSize = 96 * 1024;

std::vector<ks::FitFile> crash_files(std::int64_t i) {
  std::vector<ks::FitFile> files;
  for (int k = 0; k < kFilesPerFit; ++k)
    files.push_back({"file" + std::to_string(k) + ".bin", pattern(i, k, kFileSize + k)});
  return files;
}

// In the child: insert fits "forever", reporting each committed one.
[[noreturn]] void insert_until_killed(const std::filesystem::path& path, std::int64_t capture,
                                      int fd) {
  try {
    auto store = ks::Store::open(path);
    for (std::int64_t i = 0;; ++i) {
      store.insert_fit(capture, "crash", "{\"i\":" + std::to_string(i) + "}", "{}",
                       crash_files(i));
      if (::write(fd, &i, sizeof i) != sizeof i) ::_exit(3);
    }
  } catch (...) {
    ::_exit(2);
  }
}


}  // namespace

TEST(StoreFitFiles, SigkillMidInsertNeverLeavesAFitWithoutItsFiles) {
  TempDir dir;
  const auto path = dir / "k.db";
  std::int64_t capture = 0;
  {  // schema and capture first; no connection open across fork()
    auto store = ks::Store::open(path);
    capture = finished_capture(store);
  }
  const int kill_after[] = {3, 8};
  std::int64_t before = 0;  // fits committed by earlier rounds
  for (int round = 0; round < 2; ++round) {
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ks::test::Child child;
    child.pid = ::fork();
    ASSERT_GE(child.pid, 0);
    if (child.pid == 0) {
      ::close(fds[0]);
      insert_until_killed(path, capture, fds[1]);
    }
    ::close(fds[1]);
    std::int64_t reported = -1;
    for (int n = 0; n < kill_after[round]; ++n)
      ASSERT_TRUE(ks::test::read_int64(fds[0], reported)) << "child died early";
    ::usleep(static_cast<useconds_t>(300 + round * 900));  // land inside an insert
    ASSERT_EQ(::kill(child.pid, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child.pid, &status, 0), child.pid);
    child.pid = -1;
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
    for (std::int64_t n; ks::test::read_int64(fds[0], n);) reported = n;
    ::close(fds[0]);

    auto store = ks::Store::open(path);
    EXPECT_EQ(store.integrity_check(), "ok");
    const auto fits = store.list_fits(capture);
    // Every reported fit is there; at most the one in flight more.
    const auto n = static_cast<std::int64_t>(fits.size());
    EXPECT_GE(n, before + reported + 1);
    EXPECT_LE(n, before + reported + 2);
    EXPECT_EQ(count(store, "fit_files"), static_cast<std::int64_t>(fits.size()) * kFilesPerFit);
    for (const auto& fit : fits) {
      SCOPED_TRACE("fit " + std::to_string(fit.id) + " " + fit.params);
      const std::int64_t i = std::stoll(fit.params.substr(5));
      const auto files = store.load_fit_files(fit.id);
      ASSERT_EQ(files.size(), static_cast<std::size_t>(kFilesPerFit));
      const auto expected = crash_files(i);
      for (int k = 0; k < kFilesPerFit; ++k) {
        EXPECT_EQ(files[static_cast<std::size_t>(k)].name, expected[static_cast<std::size_t>(k)].name);
        ASSERT_TRUE(files[static_cast<std::size_t>(k)].bytes ==
                    expected[static_cast<std::size_t>(k)].bytes);
      }
    }
    before = n;
  }
}
