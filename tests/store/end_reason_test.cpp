// Schema 5: why a capture is incomplete, kept with it and carried out on
// export together with the loop's per-sample flags.
#include <gmock/gmock.h>

#include <sstream>

#include "knoblab/interchange/csv.hpp"
#include "knoblab/store/schema.hpp"
#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
namespace ki = knoblab::interchange;
using ks::test::sample_at;
using ks::test::TempDir;
using ::testing::HasSubstr;

namespace {

ks::NewCapture hapticd_capture() {
  ks::NewCapture info;
  info.knob = "fan";
  info.rate_hz = 10000;
  info.source = "hapticd";
  info.has_command = true;
  return info;
}

}  // namespace

TEST(EndReason, AnIncompleteCaptureKeepsWhyItEndedAndExportCarriesIt) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto w = store.begin_capture(hapticd_capture());
  for (int i = 0; i < 30; ++i) w.append(sample_at(i));
  w.finish_incomplete("fault: estop,velocity");
  auto ok = store.begin_capture(hapticd_capture());
  for (int i = 0; i < 30; ++i) ok.append(sample_at(i));
  ok.finish();

  const auto info = store.capture_info(w.capture_id());
  EXPECT_EQ(info->status, "incomplete");
  EXPECT_EQ(info->end_reason, "fault: estop,velocity");
  EXPECT_EQ(info->sample_count, 30);
  EXPECT_FALSE(store.capture_info(ok.capture_id())->end_reason.has_value());

  const auto c = store.load_samples(w.capture_id());
  ASSERT_NE(c.find_metadata("end_reason"), nullptr);
  EXPECT_EQ(*c.find_metadata("end_reason"), "fault: estop,velocity");
  EXPECT_EQ(store.load_samples(ok.capture_id()).find_metadata("end_reason"), nullptr);
  std::ostringstream csv;
  ki::write_csv(c, csv);
  EXPECT_THAT(csv.str(), HasSubstr("# end_reason: fault: estop,velocity\n"));
}

TEST(EndReason, IsRequiredForFinishIncompleteAndOnlyIncompleteCapturesCarryOne) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto w = store.begin_capture(hapticd_capture());
  w.append(sample_at(0));
  EXPECT_THROW(w.finish_incomplete(""), std::invalid_argument);
  w.finish();
  const auto id = std::to_string(w.capture_id());
  const auto error = ks::test::store_error(
      [&] { store.connection().exec("UPDATE captures SET end_reason = 'x' WHERE id = " + id); });
  EXPECT_THAT(error, HasSubstr("CHECK constraint failed"));
  EXPECT_FALSE(store.capture_info(w.capture_id())->end_reason.has_value());
}

// What the recorder relies on: a busy store makes finish_incomplete() throw
// without losing anything, and the same call later stores it all.
TEST(EndReason, FinishIncompleteOnABusyStoreLosesNothingAndCanBeRetried) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  store.set_busy_timeout(10);
  ks::WriterOptions options;
  options.batch_size = 100;
  auto w = store.begin_capture(hapticd_capture(), options);
  for (int i = 0; i < 150; ++i) w.append(sample_at(i));  // one batch committed, 50 waiting
  auto other = ks::sqlite::Connection::open(dir / "k.db");
  other.exec("BEGIN IMMEDIATE");
  try {
    w.finish_incomplete("store busy");
    FAIL() << "finished while another connection held the lock";
  } catch (const ks::StoreError& e) {
    EXPECT_TRUE(ks::sqlite::is_busy(e)) << e.what();
  }
  EXPECT_EQ(w.appended(), 150);
  other.exec("COMMIT");
  w.finish_incomplete("store busy");
  const auto info = store.capture_info(w.capture_id());
  EXPECT_EQ(info->status, "incomplete");
  EXPECT_EQ(info->end_reason, "store busy");
  EXPECT_EQ(info->sample_count, 150);
  EXPECT_EQ(store.load_samples(w.capture_id()).size(), 150u);
}

TEST(EndReason, UpgradingFromVersionFourKeepsEveryCaptureWithoutAReason) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 4);
    db.exec(
        "INSERT INTO captures (mode, rate_hz, source, status, sample_count)"
        " VALUES ('lab', 1000, 'hapticd', 'incomplete', 1), ('lab', 1000, 'import', 'complete', 1);"
        "INSERT INTO samples VALUES (1, 0, 0, 0, 0, 0, 0, 0, 4), (2, 0, 0, 0, 0, 0, 0, NULL, 0)");
  }
  auto store = ks::Store::open(path);
  EXPECT_EQ(store.schema_version(), ks::latest_schema_version());
  const auto captures = store.list_captures();
  ASSERT_EQ(captures.size(), 2u);
  for (const auto& c : captures) EXPECT_FALSE(c.end_reason.has_value());
  EXPECT_EQ(captures[0].status, "incomplete");
  EXPECT_EQ(store.load_samples(1).flags.at(0), 4u);
}

// Export (load_samples → CSV) and import keep each sample's flags: a capture
// whose tail was in the safe state says so after the round trip too.
TEST(ExportFlags, SurviveExportAndImport) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto w = store.begin_capture(hapticd_capture());
  for (int i = 0; i < 20; ++i) {
    auto s = sample_at(i);
    s.flags = i < 12 ? ki::kAmpEnabled : ki::kEstopActive | ki::kFaultLatched;
    w.append(s);
  }
  w.finish_incomplete("fault: estop");
  const auto exported = store.load_samples(w.capture_id());
  ki::write_csv(exported, dir / "out.csv");
  const auto back = ki::read_csv(dir / "out.csv");
  EXPECT_EQ(back.flags, exported.flags);
  const auto id = store.import_capture(back, {});
  const auto again = store.load_samples(id);
  ASSERT_EQ(again.flags.size(), 20u);
  EXPECT_EQ(again.flags, exported.flags);
  EXPECT_EQ(again.flags[11], ki::kAmpEnabled);
  EXPECT_EQ(again.flags[12], ki::kEstopActive | ki::kFaultLatched);
}
