// Batched capture writing, including the 60 s × 10 kHz zero-loss requirement.
#include <gmock/gmock.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <vector>

#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::sample_at;
using ks::test::TempDir;

namespace {

ks::NewCapture new_capture(bool command = true) {
  ks::NewCapture c;
  c.knob = "fan";
  c.rate_hz = 10000;
  c.source = "simulate";
  c.has_command = command;
  c.stimulus = R"({"kind": "sine", "amplitude_nm": 0.05, "freq_hz": 2})";
  return c;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

}  // namespace

TEST(CaptureWriter, SixtySecondsAtTenKilohertzZeroLoss) {
  constexpr std::int64_t kSamples = 600'000;  // 60 s × 10 kHz
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");

  const auto t0 = std::chrono::steady_clock::now();
  std::int64_t commits = 0;
  ks::WriterOptions options;
  options.on_commit = [&](std::int64_t) { ++commits; };
  auto w = store.begin_capture(new_capture(), options);
  for (std::int64_t i = 0; i < kSamples; ++i) w.append(sample_at(i));
  w.finish();
  const auto t1 = std::chrono::steady_clock::now();

  const auto c = store.load_samples(w.capture_id());
  const auto t2 = std::chrono::steady_clock::now();
  const auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
  std::cout << "[ timing ] write " << ms(t1 - t0) << " ms, read " << ms(t2 - t1) << " ms for "
            << kSamples << " samples\n";
  ::testing::Test::RecordProperty("write_ms", static_cast<int>(ms(t1 - t0)));
  ::testing::Test::RecordProperty("read_ms", static_cast<int>(ms(t2 - t1)));

  EXPECT_EQ(commits, kSamples / 2000);  // default batch of 2000
  ASSERT_EQ(c.size(), static_cast<std::size_t>(kSamples));
  ASSERT_TRUE(c.has_command);
  for (std::int64_t i = 0; i < kSamples; ++i) {
    const auto s = sample_at(i);
    const auto k = static_cast<std::size_t>(i);
    ASSERT_TRUE(same_bits(c.t[k], s.t) && same_bits(c.theta[k], s.theta) &&
                same_bits(c.omega[k], s.omega) && same_bits(c.alpha[k], s.alpha) &&
                same_bits(c.torque[k], s.torque) && same_bits(c.command[k], s.command))
        << "sample " << i;
  }
  const auto info = store.capture_info(w.capture_id());
  ASSERT_TRUE(info);
  EXPECT_EQ(info->status, "complete");
  EXPECT_EQ(info->sample_count, kSamples);
  EXPECT_TRUE(info->finished_at.has_value());
  EXPECT_EQ(store.connection().query_int("SELECT count(*) FROM samples"), kSamples);
  // "A few seconds": generous, but catches e.g. a commit per sample.
  EXPECT_LT(ms(t1 - t0), 30'000.0);
}

TEST(CaptureWriter, EachFullBatchIsCommittedAndVisibleToOtherProcesses) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto reader = ks::Store::open(dir / "k.db");  // a second connection, like `knoblab list`
  std::vector<std::int64_t> reported;
  ks::WriterOptions options;
  options.batch_size = 100;
  options.on_commit = [&](std::int64_t n) { reported.push_back(n); };
  auto w = store.begin_capture(new_capture(false), options);

  const auto committed_rows = [&] {
    return reader.connection().query_int("SELECT count(*) FROM samples");
  };
  for (int i = 0; i < 99; ++i) w.append(sample_at(i));
  EXPECT_EQ(committed_rows(), 0);
  EXPECT_EQ(w.appended(), 99);
  w.append(sample_at(99));
  EXPECT_EQ(committed_rows(), 100);
  EXPECT_EQ(reader.capture_info(w.capture_id())->sample_count, 100);
  EXPECT_EQ(reader.capture_info(w.capture_id())->status, "recording");
  for (int i = 100; i < 250; ++i) w.append(sample_at(i));
  EXPECT_EQ(committed_rows(), 200);
  w.flush();
  EXPECT_EQ(committed_rows(), 250);
  w.finish();
  EXPECT_EQ(reported, (std::vector<std::int64_t>{100, 200, 250}));
  const auto c = reader.load_samples(w.capture_id());
  EXPECT_EQ(c.size(), 250u);
  EXPECT_FALSE(c.has_command);
  EXPECT_TRUE(c.command.empty());
}

TEST(CaptureWriter, RejectsBadSamplesAndStaysUsable) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto w = store.begin_capture(new_capture());
  w.append(sample_at(0));
  w.append(sample_at(1));
  auto bad = sample_at(2);
  bad.torque = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(w.append(bad), std::invalid_argument);
  bad = sample_at(2);
  bad.command = std::numeric_limits<double>::infinity();
  EXPECT_THROW(w.append(bad), std::invalid_argument);
  EXPECT_THROW(w.append(sample_at(1)), std::invalid_argument);  // t repeats
  w.append(sample_at(2));
  w.finish();
  EXPECT_EQ(store.load_samples(w.capture_id()).size(), 3u);
  EXPECT_THROW(w.append(sample_at(3)), std::logic_error);
  EXPECT_THROW(w.finish(), std::logic_error);
}

TEST(CaptureWriter, DroppedWriterSavesItsBatchAndMarksIncomplete) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  std::int64_t id = 0;
  {
    ks::WriterOptions options;
    options.batch_size = 1000;
    auto w = store.begin_capture(new_capture(), options);
    id = w.capture_id();
    for (int i = 0; i < 1500; ++i) w.append(sample_at(i));
    auto moved = std::move(w);  // a moved-from writer must not close the capture
  }
  const auto info = store.capture_info(id);
  EXPECT_EQ(info->status, "incomplete");
  EXPECT_EQ(info->sample_count, 1500);
  EXPECT_EQ(store.load_samples(id).size(), 1500u);
}

TEST(CaptureWriter, WriterMayOutliveItsStore) {
  TempDir dir;
  std::optional<ks::CaptureWriter> w;
  {
    auto store = ks::Store::open(dir / "k.db");
    w.emplace(store.begin_capture(new_capture()));
  }
  for (int i = 0; i < 10; ++i) w->append(sample_at(i));
  w->finish();
  w.reset();
  auto store = ks::Store::open(dir / "k.db");
  EXPECT_EQ(store.list_captures().at(0).sample_count, 10);
}

TEST(CaptureWriter, CaptureFieldsRoundTrip) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto info = new_capture();
  info.mode = "tripod";
  info.orientation = R"({"tilt_deg": 12.5})";
  info.calibration = "{\n  \"C_cal\": 1.02,\n  \"gravity\": [1, 2, 3, 4]\n}";
  info.metadata = R"({"operator": "kh"})";
  auto w = store.begin_capture(info);
  for (int i = 0; i < 5; ++i) w.append(sample_at(i));
  const auto recording = store.capture_info(w.capture_id());
  EXPECT_EQ(recording->status, "recording");
  EXPECT_EQ(recording->writer_pid, ::getpid());
  w.finish();

  const auto all = store.list_captures();
  ASSERT_EQ(all.size(), 1u);
  const auto& c = all[0];
  EXPECT_EQ(c.knob, "fan");
  EXPECT_TRUE(c.knob_id.has_value());
  EXPECT_EQ(c.mode, "tripod");
  EXPECT_EQ(c.rate_hz, 10000.0);
  EXPECT_EQ(c.stimulus, info.stimulus);
  EXPECT_EQ(c.orientation, info.orientation);
  EXPECT_EQ(c.calibration, info.calibration);
  EXPECT_EQ(c.source, "simulate");
  EXPECT_EQ(c.status, "complete");
  EXPECT_TRUE(c.has_command);
  EXPECT_EQ(c.metadata, info.metadata);
  EXPECT_EQ(c.sample_count, 5);

  // load_samples carries the fields as one-line metadata.
  const auto s = store.load_samples(c.id);
  ASSERT_NE(s.find_metadata("calibration"), nullptr);
  EXPECT_EQ(*s.find_metadata("calibration"), "{   \"C_cal\": 1.02,   \"gravity\": [1, 2, 3, 4] }");
  EXPECT_EQ(*s.find_metadata("mode"), "tripod");
  EXPECT_EQ(*s.find_metadata("knob"), "fan");
  EXPECT_EQ(*s.find_metadata("rate_hz"), "10000");
  EXPECT_EQ(*s.find_metadata("capture_id"), std::to_string(c.id));
  EXPECT_THROW(store.load_samples(c.id + 100), ks::StoreError);
  EXPECT_FALSE(store.capture_info(c.id + 100).has_value());
}

TEST(CaptureWriter, RequiresSourceAndBatchSize) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto info = new_capture();
  info.source.clear();
  EXPECT_THROW(store.begin_capture(info), std::invalid_argument);
  ks::WriterOptions options;
  options.batch_size = 0;
  EXPECT_THROW(store.begin_capture(new_capture(), options), std::invalid_argument);
  EXPECT_TRUE(store.list_captures().empty());
}
