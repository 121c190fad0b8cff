// The schema's CHECK and FOREIGN KEY constraints are really enforced.
#include <gmock/gmock.h>

#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::store_error;
using ks::test::TempDir;
using ::testing::HasSubstr;

namespace {

ks::NewCapture new_capture() {
  ks::NewCapture c;
  c.knob = "fan";
  c.rate_hz = 10000;
  c.source = "simulate";
  return c;
}

}  // namespace

TEST(StoreConstraints, BadModeRejected) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto info = new_capture();
  info.mode = "bench";
  EXPECT_THAT(store_error([&] { store.begin_capture(info); }), HasSubstr("CHECK constraint failed"));
  EXPECT_TRUE(store.list_captures().empty());
  info.mode = "tripod";
  auto w = store.begin_capture(info);
  w.finish();
  EXPECT_EQ(store.list_captures().at(0).mode, "tripod");
}

TEST(StoreConstraints, BadStatusAndRateRejected) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto& db = store.connection();
  EXPECT_THAT(store_error([&] {
                db.exec("INSERT INTO captures (mode, rate_hz, source, status)"
                        " VALUES ('lab', 1000, 'x', 'done')");
              }),
              HasSubstr("CHECK constraint failed"));
  auto info = new_capture();
  info.rate_hz = 0;
  EXPECT_THAT(store_error([&] { store.begin_capture(info); }), HasSubstr("CHECK constraint failed"));
}

TEST(StoreConstraints, InvalidJsonRejected) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto info = new_capture();
  info.calibration = "{C_cal: oops";
  EXPECT_THAT(store_error([&] { store.begin_capture(info); }), HasSubstr("CHECK constraint failed"));
  auto w = store.begin_capture(new_capture());
  w.finish();
  EXPECT_THAT(store_error([&] { store.insert_fit(w.capture_id(), "thesis", "not json"); }),
              HasSubstr("CHECK constraint failed"));
}

TEST(StoreConstraints, ForeignKeysEnforced) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto& db = store.connection();
  EXPECT_THAT(store_error([&] {
                db.exec("INSERT INTO captures (knob_id, mode, rate_hz, source, status)"
                        " VALUES (999, 'lab', 1000, 'x', 'complete')");
              }),
              HasSubstr("FOREIGN KEY constraint failed"));
  EXPECT_THAT(store_error([&] {
                db.exec("INSERT INTO samples (capture_id, idx, t, theta, omega, alpha, torque)"
                        " VALUES (999, 0, 0, 0, 0, 0, 0)");
              }),
              HasSubstr("FOREIGN KEY constraint failed"));
  EXPECT_THAT(store_error([&] { store.insert_fit(999, "thesis", "{}"); }),
              HasSubstr("FOREIGN KEY constraint failed"));
  // A knob that has captures cannot be deleted out from under them.
  auto w = store.begin_capture(new_capture());
  w.finish();
  EXPECT_THAT(store_error([&] { db.exec("DELETE FROM knobs"); }),
              HasSubstr("FOREIGN KEY constraint failed"));
}

TEST(StoreConstraints, DeleteCaptureCascadesToSamplesAndFits) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto w = store.begin_capture(new_capture());
  for (int i = 0; i < 10; ++i) w.append(ks::test::sample_at(i));
  EXPECT_THAT(store_error([&] { store.delete_capture(w.capture_id()); }),
              HasSubstr("still recording"));
  w.finish();
  store.insert_fit(w.capture_id(), "thesis", R"({"M_acc": 1e-5})", R"({"rmse": 0.001})");
  store.delete_capture(w.capture_id());
  auto& db = store.connection();
  EXPECT_EQ(db.query_int("SELECT count(*) FROM samples"), 0);
  EXPECT_EQ(db.query_int("SELECT count(*) FROM fits"), 0);
  EXPECT_EQ(db.query_int("SELECT count(*) FROM captures"), 0);
  EXPECT_THAT(store_error([&] { store.delete_capture(w.capture_id()); }), HasSubstr("no capture"));
}

TEST(StoreConstraints, KnobCreateOrGet) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto a = store.knob_id("fan", "51 mm automobile fan knob");
  const auto b = store.knob_id("volume");
  EXPECT_NE(a, b);
  EXPECT_EQ(store.knob_id("fan"), a);
  const auto knobs = store.list_knobs();
  ASSERT_EQ(knobs.size(), 2u);
  EXPECT_EQ(knobs[0].description, "51 mm automobile fan knob");
  EXPECT_FALSE(knobs[0].created_at.empty());
  EXPECT_THROW(store.knob_id(""), std::invalid_argument);
}

TEST(StoreFits, InsertAndList) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto w = store.begin_capture(new_capture());
  w.finish();
  const auto f1 = store.insert_fit(w.capture_id(), "thesis", R"({"M_acc": 1e-5})");
  const auto f2 = store.insert_fit(w.capture_id(), "render", "{}", R"({"rmse": 0.002})");
  const auto fits = store.list_fits(w.capture_id());
  ASSERT_EQ(fits.size(), 2u);
  EXPECT_EQ(fits[0].id, f1);
  EXPECT_EQ(fits[0].model, "thesis");
  EXPECT_EQ(fits[0].params, R"({"M_acc": 1e-5})");
  EXPECT_EQ(fits[0].result, "{}");
  EXPECT_EQ(fits[1].id, f2);
  EXPECT_EQ(fits[1].result, R"({"rmse": 0.002})");
  EXPECT_FALSE(fits[1].created_at.empty());
  EXPECT_TRUE(store.list_fits(w.capture_id() + 1).empty());
}
