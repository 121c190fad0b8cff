// Schema 7: every result's provenance (tool version, input digest, options),
// a discrepancy result's report files kept like a fit's, their counts in the
// listings, and the migration from a version 6 store.
#include <gmock/gmock.h>

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

const std::string kSha(64, 'a');
const std::string kOtherSha = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";

ks::Provenance provenance(const std::string& options = R"({"model":"thesis6","filter":true})") {
  return {"0.1.0", kSha, options};
}

std::vector<ks::ResultFile> report() {
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', 0, 0, 0, 13, 0xff, 0};
  return {{"summary.md", bytes_of("| model | rms |\n")}, {"whiteness.png", png}, {"empty.svg", {}}};
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

TEST(StoreProvenance, AFitKeepsItsProvenanceAndCountsItsFiles) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  const std::vector<ks::FitFile> files = {{"fit.json", bytes_of("{}\n")}, {"a.png", bytes_of("png")}};
  const auto with = store.insert_fit(capture, "thesis6", "{}", "{}", files, provenance());
  const auto without = store.insert_fit(capture, "thesis6", "{}", "{}");

  const auto f = store.fit_info(with);
  ASSERT_TRUE(f);
  ASSERT_TRUE(f->provenance);
  EXPECT_EQ(f->provenance->tool_version, "0.1.0");
  EXPECT_EQ(f->provenance->input_sha256, kSha);
  EXPECT_EQ(f->provenance->options, R"({"model":"thesis6","filter":true})");
  EXPECT_EQ(f->file_count, 2);
  const auto g = store.fit_info(without);
  ASSERT_TRUE(g);
  EXPECT_FALSE(g->provenance);
  EXPECT_EQ(g->file_count, 0);

  const auto listed = store.list_all_fits();
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].file_count, 2);
  EXPECT_EQ(listed[0].provenance->input_sha256, kSha);
  EXPECT_EQ(listed[1].file_count, 0);
  EXPECT_EQ(store.list_fits(capture)[0].file_count, 2);
}

TEST(StoreProvenance, ADiscrepancyResultKeepsItsFilesByteForByteAndItsProvenance) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  const auto heldout = finished_capture(store);
  const auto id = store.insert_discrepancy(capture, R"({"findings":[]})", heldout, report(),
                                           provenance(R"({"heldout":{"capture":2}})"));
  const auto d = store.discrepancy_info(id);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->heldout_capture_id, heldout);
  EXPECT_EQ(d->file_count, 3);
  ASSERT_TRUE(d->provenance);
  EXPECT_EQ(d->provenance->options, R"({"heldout":{"capture":2}})");

  const auto loaded = store.load_discrepancy_files(id);
  ASSERT_EQ(loaded.size(), 3u);  // by name
  EXPECT_EQ(loaded[0].name, "empty.svg");
  EXPECT_TRUE(loaded[0].bytes.empty());
  EXPECT_EQ(loaded[1].name, "summary.md");
  EXPECT_EQ(loaded[1].bytes, report()[0].bytes);
  EXPECT_EQ(loaded[2].name, "whiteness.png");
  EXPECT_EQ(loaded[2].bytes, report()[1].bytes);
  const auto listed = store.list_discrepancy_files(id);
  ASSERT_EQ(listed.size(), 3u);
  EXPECT_EQ(listed[2].size, 10);
  EXPECT_EQ(store.list_all_discrepancies().size(), 1u);
  EXPECT_TRUE(store.list_discrepancy_files(id + 1).empty());
  EXPECT_THAT(store_error([&] { store.load_discrepancy_files(id + 1); }),
              HasSubstr("no discrepancy with id " + std::to_string(id + 1)));
}

TEST(StoreProvenance, ProvenanceOutOfShapeIsRefusedSayingWhichFieldAndStoresNothing) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  const std::string before = ks::test::checksum(store.connection());
  struct Bad {
    ks::Provenance p;
    std::string says;
  };
  const std::vector<Bad> bad = {
      {{"", kSha, "{}"}, "tool_version is empty"},
      {{"0.1.0", kSha.substr(1), "{}"}, "input_sha256 must be 64 lowercase hex digits"},
      {{"0.1.0", std::string(64, 'A'), "{}"}, "input_sha256 must be 64 lowercase hex digits"},
      {{"0.1.0", std::string(63, 'a') + "g", "{}"}, "input_sha256 must be 64 lowercase hex digits"},
      {{"0.1.0", kSha, "[1, 2]"}, "options must be a JSON object"},
      {{"0.1.0", kSha, "{\"a\": "}, "options must be a JSON object"},
  };
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.says);
    EXPECT_THAT(store_error([&] { store.insert_fit(capture, "thesis6", "{}", "{}", report(), b.p); }),
                HasSubstr("fit provenance: " + b.says));
    EXPECT_THAT(store_error([&] { store.insert_discrepancy(capture, "{}", std::nullopt, report(), b.p); }),
                HasSubstr("discrepancy provenance: " + b.says));
  }
  // The schema refuses them too, and a row with some provenance but not all.
  auto& db = store.connection();
  const std::string c = std::to_string(capture);
  for (const std::string& values :
       std::vector<std::string>{"'0.1.0', '" + kSha + "', NULL", "NULL, '" + kSha + "', '{}'",
                                "'0.1.0', 'abc', '{}'", "'0.1.0', '" + kSha + "', '[]'"}) {
    SCOPED_TRACE(values);
    EXPECT_THAT(store_error([&] {
                  db.exec("INSERT INTO fits (capture_id, model, params, tool_version, input_sha256, options)"
                          " VALUES (" + c + ", 'thesis6', '{}', " + values + ")");
                }),
                HasSubstr("CHECK constraint failed"));
    EXPECT_THAT(store_error([&] {
                  db.exec("INSERT INTO discrepancies (capture_id, result, tool_version, input_sha256, options)"
                          " VALUES (" + c + ", '{}', " + values + ")");
                }),
                HasSubstr("CHECK constraint failed"));
  }
  EXPECT_EQ(ks::test::checksum(db), before);
}

TEST(StoreProvenance, ABadDiscrepancyFileLeavesNoResultBehind) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  const std::string before = ks::test::checksum(store.connection());
  const std::vector<std::vector<ks::ResultFile>> bad = {
      {{"a.png", {}}, {"a.png", {}}},  // twice
      {{"ok.md", {}}, {"sub/dir.png", {}}},
      {{".", {}}},
      {{"..", {}}},
      {{"", {}}},
      {{std::string("x\0y", 3), {}}},
  };
  for (const auto& files : bad) {
    SCOPED_TRACE(files.back().name);
    EXPECT_THAT(store_error([&] { store.insert_discrepancy(capture, "{}", std::nullopt, files, provenance()); }),
                HasSubstr("discrepancy file"));
  }
  EXPECT_EQ(ks::test::checksum(store.connection()), before);
  EXPECT_EQ(count(store, "discrepancies"), 0);
}

TEST(StoreProvenance, DeletingTheCaptureDeletesItsDiscrepancyFiles) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto a = finished_capture(store, "fan");
  const auto b = finished_capture(store, "volume");
  store.insert_discrepancy(a, "{}", std::nullopt, report(), provenance());
  const auto kept = store.insert_discrepancy(b, "{}", std::nullopt, report(), provenance());
  EXPECT_EQ(count(store, "discrepancy_files"), 6);
  store.delete_capture(a);
  EXPECT_EQ(count(store, "discrepancy_files"), 3);
  EXPECT_EQ(store.load_discrepancy_files(kept).size(), 3u);
  EXPECT_EQ(store.integrity_check(), "ok");
}

// ---- migration ------------------------------------------------------------

TEST(StoreProvenance, Version6DatabaseIsUpgradedKeepingItsResultsWithoutProvenance) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    // A database as knoblab wrote it at schema version 6: a fit with its
    // report files, a discrepancy result with a held-out capture.
    auto db = ks::sqlite::Connection::open(path);
    db.exec("PRAGMA foreign_keys = ON");
    ks::migrate(db, 6);
    ASSERT_EQ(ks::schema_version(db), 6);
    db.exec(R"sql(
INSERT INTO knobs (id, name) VALUES (1, 'fan');
INSERT INTO captures (id, knob_id, mode, rate_hz, source, status, sample_count)
  VALUES (1, 1, 'lab', 1000, 'import', 'complete', 1), (2, 1, 'lab', 1000, 'import', 'complete', 0);
INSERT INTO samples VALUES (1, 0, 0.0, 0.1, 0.2, 0.3, 0.4, NULL, 0);
INSERT INTO fits (id, capture_id, model, params, result, created_at)
  VALUES (7, 1, 'thesis6', '{"M_acc":1e-5}', '{"rmse_Nm":0.002}', '2024-05-01T10:00:00.000Z');
INSERT INTO fit_files (fit_id, name, bytes) VALUES (7, 'fit.json', x'7b7d0a'), (7, 'a.png', x'89504e4700');
INSERT INTO discrepancies (id, capture_id, heldout_capture_id, result, created_at)
  VALUES (3, 1, 2, '{"findings":[]}', '2024-05-02T10:00:00.000Z');
)sql");
    EXPECT_EQ(db.query_int("SELECT count(*) FROM pragma_table_info('fits') WHERE name = 'tool_version'"), 0);
  }

  auto store = ks::Store::open(path);
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  EXPECT_EQ(store.integrity_check(), "ok");
  EXPECT_FALSE(store.connection().prepare("PRAGMA foreign_key_check").step());
  const auto fit = store.fit_info(7);
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->result, R"({"rmse_Nm":0.002})");
  EXPECT_EQ(fit->created_at, "2024-05-01T10:00:00.000Z");
  EXPECT_FALSE(fit->provenance);
  EXPECT_EQ(fit->file_count, 2);
  EXPECT_EQ(store.load_fit_file(7, "fit.json"), bytes_of("{}\n"));
  const auto d = store.discrepancy_info(3);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->heldout_capture_id, 2);
  EXPECT_FALSE(d->provenance);
  EXPECT_EQ(d->file_count, 0);

  // New results go in beside them with their provenance and files.
  const auto id = store.insert_discrepancy(1, "{}", std::nullopt, report(), provenance());
  EXPECT_EQ(store.discrepancy_info(id)->provenance->input_sha256, kSha);
  EXPECT_EQ(store.insert_fit(1, "thesis6", "{}", "{}", {}, provenance()), 8);
  store.delete_capture(1);
  EXPECT_EQ(count(store, "fit_files") + count(store, "discrepancy_files") + count(store, "discrepancies"), 0);
}

TEST(StoreProvenance, FailedMigrationToVersion7LeavesVersion6) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 6);
    // Step 7 adds the columns, then trips over this name.
    db.exec("CREATE TABLE discrepancy_files (x)");
  }
  EXPECT_THAT(store_error([&] { ks::Store::open(path); }), HasSubstr("migration to version 7 failed"));
  auto db = ks::sqlite::Connection::open(path);
  EXPECT_EQ(ks::schema_version(db), 6);
  EXPECT_EQ(db.query_int("SELECT count(*) FROM pragma_table_info('fits') WHERE name = 'tool_version'"), 0);
}

// ---- a capture its writer discards -----------------------------------------

TEST(StoreDiscard, ADiscardedCaptureLeavesNoRowNoSampleAndNoKnobItMade) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto kept = finished_capture(store, "fan");
  const std::string before = ks::test::checksum(store.connection());
  ks::NewCapture info;
  info.knob = "new knob";
  info.rate_hz = 1000;
  info.source = "simulate";
  ks::WriterOptions wo;
  wo.batch_size = 10;
  auto w = store.begin_capture(info, wo);
  for (int i = 0; i < 25; ++i) w.append(ks::test::sample_at(i));
  ASSERT_EQ(w.committed(), 20);
  w.discard();
  EXPECT_EQ(ks::test::checksum(store.connection()), before);
  EXPECT_EQ(store.list_captures().size(), 1u);
  EXPECT_EQ(store.list_captures()[0].id, kept);
  EXPECT_EQ(store.integrity_check(), "ok");
  EXPECT_THROW(w.append(ks::test::sample_at(25)), std::logic_error);
}

TEST(StoreDiscard, ADiscardedCaptureKeepsAKnobOtherCapturesUse) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  finished_capture(store, "fan");
  ks::NewCapture info;
  info.knob = "fan";
  info.rate_hz = 1000;
  info.source = "simulate";
  auto w = store.begin_capture(info);
  w.append(ks::test::sample_at(0));
  w.discard();
  ASSERT_EQ(store.list_knobs().size(), 1u);
  EXPECT_EQ(store.list_knobs()[0].name, "fan");
  EXPECT_EQ(count(store, "captures"), 1);
}
