// The recorder on its own, fed loop records by hand: what ends up in the
// store when faults latch, when the ring drops records, when another writer
// holds the store and when the store fails.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <future>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "knoblab/hapticd/recorder.hpp"
#include "knoblab/store/store.hpp"

#include "held_commit.hpp"
#include "temp_db.hpp"

namespace knoblab::hapticd {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

using testing::HeldCommit;
using testing::TempDb;

store::NewCapture defaults() {
  store::NewCapture d;
  d.knob = "fan";
  d.rate_hz = 10000;
  d.source = "hapticd";
  return d;
}

// Cycle `seq` of a 10 kHz loop that started at CLOCK_MONOTONIC 1 s.
LoopRecord record(std::uint64_t seq, std::uint32_t recording, std::uint32_t faults = 0) {
  LoopRecord r;
  r.seq = seq;
  r.recording_id = recording;
  r.faults = faults;
  r.now_ns = 1'000'000'000 + static_cast<std::int64_t>(seq) * 100'000;
  r.sample.t = static_cast<double>(seq) * 1e-4;
  r.sample.theta = 0.001 * static_cast<double>(seq);
  r.sample.command = 0.5;
  r.sample.flags = faults ? interchange::kFaultLatched : interchange::kAmpEnabled;
  r.mode = Mode::Render;
  return r;
}

// Feeds cycles [from, to) as the writer thread does: a pump every 512.
void feed(Recorder& rec, std::uint64_t from, std::uint64_t to, std::uint32_t recording,
          std::uint32_t faults = 0) {
  for (std::uint64_t s = from; s < to; ++s) {
    rec.take(record(s, recording, faults));
    if ((s + 1) % 512 == 0) rec.pump();
  }
  rec.pump();
}

// Pumps until everything taken is stored (or gives up after a while).
void drain(Recorder& rec) {
  for (int i = 0; i < 10000 && !rec.idle(); ++i) rec.pump();
  ASSERT_TRUE(rec.idle());
}

store::Store reader(const TempDb& db) {
  store::OpenOptions o;
  o.read_only = true;
  return store::Store::open(db.path(), o);
}

TEST(Recorder, ARecordingDuringWhichAFaultLatchedIsStoredIncompleteWithTheFault) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  Recorder rec(&s, defaults());
  feed(rec, 0, 100, 0);
  feed(rec, 100, 150, 1);
  feed(rec, 150, 400, 1, kFaultEstop | kFaultVelocity);  // the motor held safe from here
  feed(rec, 400, 500, 0, kFaultEstop);
  feed(rec, 500, 700, 2);  // cleared: the next recording is clean
  feed(rec, 700, 710, 0);
  rec.close();
  drain(rec);

  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 2u);
  EXPECT_FALSE(fin[0].complete);
  EXPECT_EQ(fin[0].end_reason, "fault: estop,velocity");
  EXPECT_EQ(fin[0].samples, 300);
  EXPECT_TRUE(fin[1].complete);
  EXPECT_EQ(fin[1].end_reason, "");

  auto r = reader(db);
  const auto faulted = r.capture_info(fin[0].capture_id);
  EXPECT_EQ(faulted->status, "incomplete");
  EXPECT_EQ(faulted->end_reason, "fault: estop,velocity");
  EXPECT_EQ(faulted->sample_count, 300);
  const auto clean = r.capture_info(fin[1].capture_id);
  EXPECT_EQ(clean->status, "complete");
  EXPECT_FALSE(clean->end_reason.has_value());
  EXPECT_EQ(clean->sample_count, 200);
}

// A slow loop fills a batch slowly (2000 samples are 8 s at 250 Hz): the
// recorder commits on time as well, so a power cut loses little of it.
TEST(Recorder, ARecordingIsCommittedEveryCommitIntervalNotOnlyInFullBatches) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  RecorderOptions options;
  options.commit_interval_s = 0.00995;  // 99.5 cycles of the 10 kHz records
  Recorder rec(&s, defaults(), options);
  for (std::uint64_t seq = 0; seq < 330; ++seq) {  // still recording: 330 samples, 0.033 s
    rec.take(record(seq, 1));
    if ((seq + 1) % 40 == 0) rec.pump();  // a store thread that keeps up
  }
  rec.pump();

  const auto info = reader(db).capture_info(1);
  ASSERT_TRUE(info.has_value());
  EXPECT_EQ(info->status, "recording");
  // A commit once a pump's newest sample is 100 cycles or more after the
  // oldest uncommitted one: after the pumps that end at 119 and 239; the
  // last 90 wait for the next.
  EXPECT_EQ(info->sample_count, 240);
}

// A store that fell behind (its last fsync took seconds) finds everything
// that waited in one batch and commits it at once, instead of one commit per
// interval of the recording, each waiting for its own fsync.
TEST(Recorder, AStoreThatFellBehindCatchesUpInOneCommitPerBatch) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  std::vector<std::int64_t> commits;
  RecorderOptions options;
  options.on_commit = [&](std::int64_t committed) { commits.push_back(committed); };
  options.max_commit_samples = 4000;
  Recorder rec(&s, defaults(), options);
  for (std::uint64_t seq = 0; seq < 9000; ++seq) rec.take(record(seq, 1));  // 0.9 s waited
  rec.pump();
  EXPECT_EQ(commits, (std::vector<std::int64_t>{4000, 8000}));  // the last 0.1 s waits for more
  for (std::uint64_t seq = 9000; seq < 9010; ++seq) rec.take(record(seq, 0));
  rec.close();
  drain(rec);
  EXPECT_EQ(commits, (std::vector<std::int64_t>{4000, 8000, 9000}));
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 1u);
  EXPECT_TRUE(fin[0].complete) << fin[0].end_reason;
  EXPECT_EQ(reader(db).capture_info(fin[0].capture_id)->sample_count, 9000);
}

// The store thread held inside a commit (a disk that takes its time to
// fsync): the ring thread goes on taking records. Were take() to wait for
// the commit, the taker below would never finish while the commit is held.
TEST(Recorder, TakingRecordsNeverWaitsForACommitInProgress) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  HeldCommit disk;
  Recorder rec(&s, defaults(), disk.options());
  for (std::uint64_t seq = 0; seq < 3000; ++seq) rec.take(record(seq, 1));
  std::thread store_thread([&] {
    while (!rec.idle()) {
      rec.pump();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  const bool in_commit = disk.wait_entered(std::chrono::seconds(30));
  auto taker = std::async(std::launch::async, [&] {
    for (std::uint64_t seq = 3000; seq < 23000; ++seq) rec.take(record(seq, 1));
    rec.take(record(23000, 0));
    rec.close();
  });
  const bool took = taker.wait_for(std::chrono::seconds(30)) == std::future_status::ready;
  const RecorderStats during = rec.stats();
  disk.release();
  taker.get();
  store_thread.join();

  EXPECT_TRUE(in_commit) << "the store thread never committed";
  EXPECT_TRUE(took) << "take() waited for the commit in progress";
  EXPECT_EQ(during.buffered, 23000u);  // the 3000 being committed count until the commit returns
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 1u);
  EXPECT_TRUE(fin[0].complete) << fin[0].end_reason;
  EXPECT_EQ(fin[0].samples, 23000);
  const auto c = reader(db).load_samples(fin[0].capture_id);
  ASSERT_EQ(c.size(), 23000u);
  for (std::size_t i = 0; i < c.size(); ++i) ASSERT_EQ(c.t[i], static_cast<double>(i) * 1e-4);
}

TEST(Recorder, ARingDropWhileNotRecordingDoesNotMarkTheNextRecordingIncomplete) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  Recorder rec(&s, defaults());
  feed(rec, 0, 50, 0);
  feed(rec, 80, 100, 0);  // cycles 50..79 lost while idle
  feed(rec, 100, 300, 1);
  feed(rec, 300, 310, 0);
  rec.close();
  drain(rec);
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 1u);
  EXPECT_TRUE(fin[0].complete) << fin[0].end_reason;
  EXPECT_EQ(reader(db).capture_info(fin[0].capture_id)->status, "complete");
}

TEST(Recorder, RingDropsAreChargedToTheRecordingThatLostTheSamples) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  Recorder rec(&s, defaults());
  feed(rec, 0, 100, 0);
  feed(rec, 100, 150, 1);
  feed(rec, 162, 200, 1);  // 12 of recording 1 lost
  feed(rec, 200, 300, 0);
  feed(rec, 300, 400, 2);  // untouched
  feed(rec, 400, 450, 0);
  feed(rec, 455, 500, 3);  // lost at its very start: 5 that may have been its own
  feed(rec, 500, 510, 0);
  rec.close();
  drain(rec);
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 3u);
  EXPECT_EQ(fin[0].end_reason, "ring dropped 12 samples");
  EXPECT_EQ(fin[0].samples, 88);
  EXPECT_TRUE(fin[1].complete) << fin[1].end_reason;
  EXPECT_EQ(fin[2].end_reason, "ring dropped up to 5 samples");
  auto r = reader(db);
  EXPECT_EQ(r.capture_info(fin[0].capture_id)->end_reason, "ring dropped 12 samples");
  EXPECT_EQ(r.capture_info(fin[1].capture_id)->status, "complete");
  EXPECT_EQ(r.capture_info(fin[2].capture_id)->status, "incomplete");
}

TEST(Recorder, KeepsEverySampleWhileAnotherConnectionHoldsTheWriteLock) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  Recorder rec(&s, defaults());
  auto other = store::sqlite::Connection::open(db.path());
  other.exec("BEGIN IMMEDIATE");  // e.g. an import's transaction
  feed(rec, 0, 100, 0);
  feed(rec, 100, 20100, 1);
  store::BiometricSample b{7, 1.5, 1e-6, 2e-6, 3e-6};  // monotonic 1.5 s = t 0.49 s
  rec.add_biometrics(b);
  feed(rec, 20100, 20200, 0);
  for (int i = 0; i < 5; ++i) rec.pump();
  const RecorderStats busy = rec.stats();
  EXPECT_EQ(busy.buffered, 20000u);
  EXPECT_GT(busy.retries, 0u);
  EXPECT_FALSE(rec.idle());
  EXPECT_TRUE(rec.take_finished().empty());
  EXPECT_FALSE(rec.safe_state_needed());
  EXPECT_TRUE(reader(db).list_captures().empty());

  other.exec("COMMIT");
  rec.close();
  drain(rec);
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 1u);
  EXPECT_TRUE(fin[0].complete) << fin[0].end_reason;
  EXPECT_EQ(fin[0].samples, 20000);
  auto r = reader(db);
  const auto info = r.capture_info(fin[0].capture_id);
  EXPECT_EQ(info->status, "complete");
  EXPECT_EQ(info->sample_count, 20000);
  const auto c = r.load_samples(fin[0].capture_id);
  ASSERT_EQ(c.size(), 20000u);
  // On the recording's clock: from its first record (cycle 100, 1.01 s).
  for (std::size_t i = 0; i < c.size(); ++i) ASSERT_EQ(c.t[i], static_cast<double>(i) * 1e-4);
  const auto bio = r.load_biometrics(fin[0].capture_id);
  ASSERT_EQ(bio.size(), 1u);
  EXPECT_NEAR(bio[0].t, 0.49, 1e-9);
  const RecorderStats after = rec.stats();
  EXPECT_EQ(after.buffered, 0u);
  EXPECT_EQ(after.max_buffered, 20000u);
  EXPECT_EQ(after.failed, 0u);
}

// A biometrics box restarted mid-trial counts from 0 again: the trial once
// lost all its biometrics to the store's UNIQUE (capture_id, seq).
TEST(Recorder, ABiometricsBoxWhoseCounterRestartsMidRecordingKeepsEverySampleInOrder) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  Recorder rec(&s, defaults());
  feed(rec, 0, 100, 0);
  feed(rec, 100, 2100, 1);
  // The recording's t = 0 is its first record's monotonic 1.01 s; the box
  // restarts after its sample 42.
  const std::vector<std::pair<std::int64_t, double>> box = {{40, 1.01}, {41, 1.02}, {42, 1.03}, {0, 1.10}, {1, 1.11}};
  for (const auto& [counter, when] : box) rec.add_biometrics({counter, when, 1e-6, 2e-6, 3e-6});
  feed(rec, 2100, 2200, 0);
  rec.close();
  drain(rec);
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 1u);
  EXPECT_TRUE(fin[0].complete) << fin[0].end_reason;
  const auto bio = reader(db).load_biometrics(fin[0].capture_id);
  ASSERT_EQ(bio.size(), box.size());
  for (std::size_t i = 0; i < bio.size(); ++i) {
    EXPECT_EQ(bio[i].seq, 40 + static_cast<std::int64_t>(i)) << i;
    EXPECT_NEAR(bio[i].t, box[i].second - 1.01, 1e-9) << i;
  }
}

TEST(Recorder, ARecordingThatOutgrowsItsBufferIsCutAndAsksForTheSafeState) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  RecorderOptions options;
  options.max_buffered = 1000;
  Recorder rec(&s, defaults(), options);
  EXPECT_EQ(rec.stats().capacity, 1000u);
  auto other = store::sqlite::Connection::open(db.path());
  other.exec("BEGIN IMMEDIATE");
  feed(rec, 0, 900, 1);
  EXPECT_FALSE(rec.safe_state_needed());
  feed(rec, 900, 1500, 1);
  EXPECT_TRUE(rec.safe_state_needed());
  EXPECT_FALSE(rec.safe_state_needed());  // once per recording
  EXPECT_EQ(rec.stats().buffered, 1000u);
  EXPECT_EQ(rec.stats().failed, 1u);
  feed(rec, 1500, 1600, 1, kFaultRecording);  // the loop stops it a little later
  feed(rec, 1600, 1700, 0, kFaultRecording);
  other.exec("COMMIT");
  rec.close();
  drain(rec);
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 1u);
  EXPECT_FALSE(fin[0].complete);
  EXPECT_THAT(fin[0].end_reason, StartsWith("store busy"));
  EXPECT_EQ(fin[0].samples, 1000);
  const auto info = reader(db).capture_info(fin[0].capture_id);
  EXPECT_EQ(info->status, "incomplete");
  EXPECT_EQ(info->end_reason, fin[0].end_reason);
  EXPECT_EQ(info->sample_count, 1000);
}

TEST(Recorder, AStoreErrorOtherThanBusyCutsTheRecordingAndAsksForTheSafeState) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  Recorder rec(&s, defaults());
  s.connection().exec(
      "CREATE TEMP TRIGGER disk_on_fire BEFORE INSERT ON samples WHEN NEW.idx = 3000"
      " BEGIN SELECT RAISE(ABORT, 'disk on fire'); END");
  feed(rec, 0, 6000, 1);
  EXPECT_TRUE(rec.safe_state_needed());
  EXPECT_EQ(rec.stats().buffered, 0u);  // nothing more of it is kept
  feed(rec, 6000, 6100, 0);
  s.connection().exec("DROP TRIGGER disk_on_fire");
  feed(rec, 6100, 6300, 2);  // the recorder goes on with the next one
  feed(rec, 6300, 6310, 0);
  rec.close();
  drain(rec);
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 2u);
  EXPECT_FALSE(fin[0].complete);
  EXPECT_THAT(fin[0].end_reason, StartsWith("store error: "));
  EXPECT_THAT(fin[0].end_reason, HasSubstr("disk on fire"));
  // Committed once 0.25 s had waited (pumps every 512: at 2560); the next
  // commit, at 5120, met the fire.
  EXPECT_EQ(fin[0].samples, 2560);
  EXPECT_TRUE(fin[1].complete) << fin[1].end_reason;
  auto r = reader(db);
  const auto cut = r.capture_info(fin[0].capture_id);
  EXPECT_EQ(cut->status, "incomplete");
  EXPECT_EQ(cut->sample_count, 2560);
  EXPECT_THAT(cut->end_reason.value_or(""), HasSubstr("disk on fire"));
  EXPECT_EQ(r.capture_info(fin[1].capture_id)->sample_count, 200);
}

// hapticd exiting while another writer still holds the store: what is
// buffered is given up (the daemon waits first), and the recording says why.
TEST(Recorder, GivingUpAtShutdownReportsTheRecordingIncompleteAndEmptiesTheBuffer) {
  TempDb db{"recorder"};
  store::Store s = store::Store::open(db.path());
  Recorder rec(&s, defaults());
  auto other = store::sqlite::Connection::open(db.path());
  other.exec("BEGIN IMMEDIATE");
  feed(rec, 0, 3000, 1);
  rec.close();
  rec.pump();
  EXPECT_FALSE(rec.idle());
  rec.abandon_all("store busy at shutdown");
  EXPECT_TRUE(rec.idle());
  EXPECT_EQ(rec.stats().buffered, 0u);
  const auto fin = rec.take_finished();
  ASSERT_EQ(fin.size(), 1u);
  EXPECT_FALSE(fin[0].complete);
  EXPECT_EQ(fin[0].end_reason, "store busy at shutdown");
  EXPECT_EQ(fin[0].capture_id, 0);  // its row was never written
  other.exec("COMMIT");
  EXPECT_TRUE(reader(db).list_captures().empty());
}

}  // namespace
}  // namespace knoblab::hapticd
