// Discrepancy results kept beside their capture: byte-exact round trips,
// refusals that store nothing, what deleting either capture does, and the
// migration that added the table.
#include <gmock/gmock.h>

#include <string>

#include "knoblab/store/schema.hpp"
#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::store_error;
using ks::test::TempDir;
using ::testing::HasSubstr;

namespace {

// Shaped like discovery::to_json (docs/discrepancy.md), with what a byte-exact
// store must keep: indentation, a non-ASCII unit, escapes, exponents, null.
const std::string kResult = R"({
  "base": {
    "params": {
      "M_acc": 1.2345678901234567e-05,
      "P_pos": 0.5235987755982988
    },
    "rmse_Nm": 0.00073,
    "heldout_rmse_Nm": 0.00074,
    "whiteness_p": 1e-300,
    "independence_p": null
  },
  "findings": [
    {
      "effect": "periodic_torque",
      "confidence": 0.81,
      "where": "over position, 17.3 cycles/rev",
      "explanation": "a torque of 0.99 mN·m \"beside\" the detents\ttabbed"
    }
  ],
  "tentative_findings": [],
  "min_reported_gain": 0.2,
  "train_rows": 6000,
  "heldout_rows": 6000,
  "blocks": 32,
  "seconds": 1.25
})";

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

TEST(StoreDiscrepancies, AStoredResultComesBackByteEqual) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store, "fan");
  const auto heldout = finished_capture(store, "fan");
  const auto id = store.insert_discrepancy(capture, kResult);
  const auto with_heldout = store.insert_discrepancy(capture, R"({"findings":[]})", heldout);
  EXPECT_GT(with_heldout, id);

  const auto info = store.discrepancy_info(id);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->id, id);
  EXPECT_EQ(info->capture_id, capture);
  EXPECT_FALSE(info->heldout_capture_id);
  EXPECT_EQ(info->result, kResult);
  EXPECT_EQ(info->created_at.size(), 24u) << info->created_at;  // 2025-01-02T03:04:05.678Z

  const auto listed = store.list_discrepancies(capture);
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].id, id);
  EXPECT_EQ(listed[0].result, kResult);
  EXPECT_EQ(listed[1].id, with_heldout);
  EXPECT_EQ(listed[1].heldout_capture_id, heldout);
  EXPECT_EQ(listed[1].result, R"({"findings":[]})");
  // Listed under the capture analysed, not the one held out.
  EXPECT_TRUE(store.list_discrepancies(heldout).empty());
  EXPECT_FALSE(store.discrepancy_info(with_heldout + 1));
  EXPECT_FALSE(store.discrepancy_info(0));
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST(StoreDiscrepancies, AnUnknownCaptureAndInvalidJsonAreRefusedAndLeaveNothing) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  store.insert_discrepancy(capture, "{}");
  const std::string before = ks::test::checksum(store.connection());
  const auto unknown = capture + 100;

  EXPECT_THAT(store_error([&] { store.insert_discrepancy(unknown, kResult); }),
              HasSubstr("no capture with id " + std::to_string(unknown)));
  EXPECT_THAT(store_error([&] { store.insert_discrepancy(capture, kResult, unknown); }),
              HasSubstr("no held-out capture with id " + std::to_string(unknown)));
  for (const std::string& bad : {std::string("not json"), std::string(), std::string("{\"a\": 1"),
                                 std::string("{a: 1}"), kResult + ","}) {
    SCOPED_TRACE("result '" + bad + "'");
    EXPECT_THAT(store_error([&] { store.insert_discrepancy(capture, bad); }),
                HasSubstr("discrepancy result of capture " + std::to_string(capture) +
                          " is not valid JSON"));
  }
  // The schema refuses them too, for a writer that goes round the API.
  auto& db = store.connection();
  EXPECT_THAT(store_error([&] {
                db.exec("INSERT INTO discrepancies (capture_id, result) VALUES (" +
                        std::to_string(unknown) + ", '{}')");
              }),
              HasSubstr("FOREIGN KEY constraint failed"));
  EXPECT_THAT(store_error([&] {
                db.exec("INSERT INTO discrepancies (capture_id, heldout_capture_id, result) VALUES (" +
                        std::to_string(capture) + ", " + std::to_string(unknown) + ", '{}')");
              }),
              HasSubstr("FOREIGN KEY constraint failed"));
  EXPECT_THAT(store_error([&] {
                db.exec("INSERT INTO discrepancies (capture_id, result) VALUES (" +
                        std::to_string(capture) + ", 'not json')");
              }),
              HasSubstr("CHECK constraint failed"));

  EXPECT_EQ(ks::test::checksum(db), before);
  EXPECT_EQ(count(store, "discrepancies"), 1);
  EXPECT_FALSE(db.in_transaction());
}

TEST(StoreDiscrepancies, DeletingTheCaptureDeletesItsDiscrepancies) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto a = finished_capture(store, "fan");
  const auto b = finished_capture(store, "volume");
  const auto da1 = store.insert_discrepancy(a, kResult);
  const auto da2 = store.insert_discrepancy(a, "{}", b);
  const auto db1 = store.insert_discrepancy(b, kResult);

  store.delete_capture(a);
  EXPECT_FALSE(store.discrepancy_info(da1));
  EXPECT_FALSE(store.discrepancy_info(da2));
  EXPECT_TRUE(store.list_discrepancies(a).empty());
  EXPECT_EQ(count(store, "discrepancies"), 1);
  // The other capture's result is untouched.
  const auto kept = store.discrepancy_info(db1);
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->capture_id, b);
  EXPECT_EQ(kept->result, kResult);
  EXPECT_EQ(store.integrity_check(), "ok");
}

TEST(StoreDiscrepancies, DeletingTheHeldOutCaptureKeepsTheResultWithHeldOutNull) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto trained = finished_capture(store);
  const auto heldout = finished_capture(store);
  const auto id = store.insert_discrepancy(trained, kResult, heldout);
  const auto created = store.discrepancy_info(id)->created_at;

  store.delete_capture(heldout);
  const auto info = store.discrepancy_info(id);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->capture_id, trained);
  EXPECT_FALSE(info->heldout_capture_id);
  EXPECT_EQ(info->result, kResult);
  EXPECT_EQ(info->created_at, created);
  EXPECT_EQ(store.connection().query_int(
                "SELECT count(*) FROM discrepancies WHERE heldout_capture_id IS NULL"),
            1);
  EXPECT_FALSE(store.connection().prepare("PRAGMA foreign_key_check").step());
}

TEST(StoreDiscrepancies, AReadOnlyStoreListsThemButStoresNone) {
  TempDir dir;
  const auto path = dir / "k.db";
  std::int64_t capture = 0, id = 0;
  {
    auto store = ks::Store::open(path);
    capture = finished_capture(store);
    id = store.insert_discrepancy(capture, kResult);
  }
  ks::OpenOptions read_only;
  read_only.read_only = true;
  auto store = ks::Store::open(path, read_only);
  const auto listed = store.list_discrepancies(capture);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].id, id);
  EXPECT_EQ(listed[0].result, kResult);
  EXPECT_FALSE(store_error([&] { store.insert_discrepancy(capture, "{}"); }).empty());
  EXPECT_EQ(store.list_discrepancies(capture).size(), 1u);
}

// ---- migration ------------------------------------------------------------

TEST(StoreDiscrepancies, Version5DatabaseIsUpgradedKeepingItsData) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    // A database as knoblab wrote it before discrepancy results were kept.
    auto db = ks::sqlite::Connection::open(path);
    db.exec("PRAGMA foreign_keys = ON");
    ks::migrate(db, 5);
    ASSERT_EQ(ks::schema_version(db), 5);
    db.exec(R"sql(
INSERT INTO knobs (id, name) VALUES (1, 'fan');
INSERT INTO captures (id, knob_id, mode, rate_hz, source, status, sample_count)
  VALUES (1, 1, 'lab', 1000, 'import', 'complete', 1);
INSERT INTO samples VALUES (1, 0, 0.0, 0.1, 0.2, 0.3, 0.4, NULL, 0);
INSERT INTO fits (id, capture_id, model, params, result, created_at)
  VALUES (7, 1, 'thesis6', '{"M_acc":1e-5}', '{"rmse_Nm":0.002}', '2024-05-01T10:00:00.000Z');
)sql");
    EXPECT_EQ(db.query_int("SELECT count(*) FROM sqlite_schema WHERE name = 'discrepancies'"), 0);
  }

  auto store = ks::Store::open(path);
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  EXPECT_GE(store.schema_version(), 6);
  EXPECT_EQ(store.integrity_check(), "ok");
  EXPECT_FALSE(store.connection().prepare("PRAGMA foreign_key_check").step());
  EXPECT_EQ(store.connection().query_int(
                "SELECT count(*) FROM sqlite_schema WHERE type = 'index' AND name IN"
                " ('discrepancies_by_capture', 'discrepancies_by_heldout')"),
            2);
  const auto old_fit = store.fit_info(7);
  ASSERT_TRUE(old_fit);
  EXPECT_EQ(old_fit->result, R"({"rmse_Nm":0.002})");
  EXPECT_EQ(store.load_samples(1).size(), 1u);
  EXPECT_TRUE(store.list_discrepancies(1).empty());

  const auto id = store.insert_discrepancy(1, kResult);
  EXPECT_EQ(store.discrepancy_info(id)->result, kResult);
  store.delete_capture(1);
  EXPECT_EQ(count(store, "discrepancies"), 0);
}

TEST(StoreDiscrepancies, FailedMigrationToVersion6LeavesVersion5) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 5);
    // Step 6 creates the table and its first index, then trips over this.
    db.exec("CREATE TABLE discrepancies_by_heldout (x)");
  }
  EXPECT_THAT(store_error([&] { ks::Store::open(path); }),
              HasSubstr("migration to version 6 failed"));
  auto db = ks::sqlite::Connection::open(path);
  EXPECT_EQ(ks::schema_version(db), 5);
  EXPECT_EQ(db.query_int("SELECT count(*) FROM sqlite_schema WHERE name IN"
                         " ('discrepancies', 'discrepancies_by_capture')"),
            0);
}
