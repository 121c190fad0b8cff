// The shared-memory telemetry ring within one process: decimation with
// min/max, header checks, overrun accounting, and a writer and readers
// racing in threads.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "knoblab/control/telemetry_layout.hpp"
#include "knoblab/control/telemetry_reader.hpp"
#include "knoblab/control/telemetry_writer.hpp"
#include "telemetry_support.hpp"

namespace knoblab::control::test {
namespace {

TelemetryConfig config_for(const char* what, std::uint32_t capacity, std::uint32_t decimation) {
  TelemetryConfig c;
  c.shm_name = unique_shm_name(what);
  c.capacity = capacity;
  c.decimation = decimation;
  return c;
}

TEST(Telemetry, DecimationKeepsTheLastSampleAndTheWindowsExtremes) {
  const auto cfg = config_for("decim", 64, 10);
  TelemetryWriter w(cfg);
  TelemetryReader r(cfg.shm_name, TelemetryReader::Start::oldest);
  for (int i = 0; i < 100; ++i) {
    TelemetrySample s;
    s.t = i * 1e-4;
    s.theta = i * 0.01;
    s.omega = -i;
    s.torque = 0.001 * (i % 10);
    if (i == 37) s.torque = 5.0;    // spikes a plain subsample would miss
    if (i == 52) s.torque = -5.0;
    s.command = 0.5 * i;
    s.mode = 1;
    s.fault_bits = i == 23 ? 0x4u : 0u;  // a fault lasting one cycle
    w.push(s);
  }
  EXPECT_EQ(w.records_published(), 10u);
  std::vector<TelemetryRecord> out(32);
  const auto res = r.read(out);
  ASSERT_EQ(res.count, 10u);
  EXPECT_EQ(res.lost, 0u);
  EXPECT_EQ(res.first_sequence, 0u);
  for (std::size_t k = 0; k < 10; ++k) {
    const auto& rec = out[k];
    const int last = static_cast<int>(k) * 10 + 9;
    EXPECT_DOUBLE_EQ(rec.t, last * 1e-4);
    EXPECT_DOUBLE_EQ(rec.theta, last * 0.01);
    EXPECT_DOUBLE_EQ(rec.omega, -last);
    EXPECT_DOUBLE_EQ(rec.command, 0.5 * last);
    EXPECT_DOUBLE_EQ(rec.torque, 0.009);
    EXPECT_DOUBLE_EQ(rec.torque_max, k == 3 ? 5.0 : 0.009) << "window " << k;
    EXPECT_DOUBLE_EQ(rec.torque_min, k == 5 ? -5.0 : 0.0) << "window " << k;
    EXPECT_EQ(rec.fault_bits, k == 2 ? 0x4u : 0u) << "window " << k;
    EXPECT_EQ(rec.mode, 1u);
  }
  EXPECT_EQ(r.read(out).count, 0u) << "nothing new";
}

TEST(Telemetry, DecimationOfOnePassesEverySample) {
  const auto cfg = config_for("d1", 16, 1);
  TelemetryWriter w(cfg);
  TelemetryReader r(cfg.shm_name, TelemetryReader::Start::oldest);
  for (std::uint64_t i = 0; i < 5; ++i) w.push(counter_sample(i));
  std::vector<TelemetryRecord> out(8);
  ASSERT_EQ(r.read(out).count, 5u);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_TRUE(consistent(out[k], 1)) << k;
}

TEST(Telemetry, HeaderDescribesTheRing) {
  auto cfg = config_for("hdr", 256, 10);
  cfg.loop_rate_hz = 10000;
  TelemetryWriter w(cfg);
  TelemetryReader r(cfg.shm_name);
  EXPECT_EQ(r.capacity(), 256u);
  EXPECT_EQ(r.decimation(), 10u);
  EXPECT_DOUBLE_EQ(r.record_rate_hz(), 1000.0);
  EXPECT_FALSE(r.writer_closed());
  struct stat st{};
  ASSERT_EQ(::stat(("/dev/shm" + cfg.shm_name).c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
}

TEST(Telemetry, NewestReaderSeesOnlyLaterRecords) {
  const auto cfg = config_for("newest", 16, 1);
  TelemetryWriter w(cfg);
  for (std::uint64_t i = 0; i < 5; ++i) w.push(counter_sample(i));
  TelemetryReader r(cfg.shm_name);  // Start::newest
  std::vector<TelemetryRecord> out(8);
  EXPECT_EQ(r.read(out).count, 0u);
  w.push(counter_sample(5));
  const auto res = r.read(out);
  ASSERT_EQ(res.count, 1u);
  EXPECT_EQ(res.first_sequence, 5u);
  EXPECT_EQ(out[0].t, 5.0);
}

TEST(Telemetry, OverrunIsDetectedCountedAndResynchronised) {
  const auto cfg = config_for("overrun", 16, 1);
  TelemetryWriter w(cfg);
  TelemetryReader r(cfg.shm_name, TelemetryReader::Start::oldest);
  for (std::uint64_t i = 0; i < 100; ++i) w.push(counter_sample(i));  // laps the reader 6 times
  std::vector<TelemetryRecord> out(64);
  const auto res = r.read(out);
  // Skips to half a ring behind the writer: records 92..99.
  EXPECT_EQ(res.lost, 92u);
  EXPECT_EQ(res.first_sequence, 92u);
  ASSERT_EQ(res.count, 8u);
  for (std::size_t k = 0; k < res.count; ++k) {
    EXPECT_EQ(out[k].t, static_cast<double>(92 + k));
    EXPECT_TRUE(consistent(out[k], 1));
  }
  EXPECT_EQ(r.lost_total(), 92u);
  for (std::uint64_t i = 100; i < 105; ++i) w.push(counter_sample(i));
  const auto again = r.read(out);
  EXPECT_EQ(again.lost, 0u);
  EXPECT_EQ(again.count, 5u);
  EXPECT_EQ(again.first_sequence, 100u);
  EXPECT_EQ(r.cursor(), 105u);
}

TEST(Telemetry, ExactlyOneRingBehindIsNotAnOverrun) {
  const auto cfg = config_for("full", 16, 1);
  TelemetryWriter w(cfg);
  TelemetryReader r(cfg.shm_name, TelemetryReader::Start::oldest);
  for (std::uint64_t i = 0; i < 16; ++i) w.push(counter_sample(i));
  std::vector<TelemetryRecord> out(32);
  const auto res = r.read(out);
  EXPECT_EQ(res.lost, 0u);
  EXPECT_EQ(res.count, 16u);
  w.push(counter_sample(16));
  w.push(counter_sample(17));
  EXPECT_EQ(r.read(out).count, 2u);
}

TEST(Telemetry, ReadersHaveTheirOwnCursors) {
  const auto cfg = config_for("cursors", 64, 1);
  TelemetryWriter w(cfg);
  TelemetryReader a(cfg.shm_name, TelemetryReader::Start::oldest), b(cfg.shm_name, TelemetryReader::Start::oldest);
  for (std::uint64_t i = 0; i < 10; ++i) w.push(counter_sample(i));
  std::vector<TelemetryRecord> out(4);
  EXPECT_EQ(a.read(out).count, 4u);
  EXPECT_EQ(a.cursor(), 4u);
  EXPECT_EQ(b.cursor(), 0u) << "a's reading does not move b";
  std::vector<TelemetryRecord> all(16);
  EXPECT_EQ(b.read(all).count, 10u);
}

TEST(Telemetry, ReaderSeesTheWriterClose) {
  const auto cfg = config_for("close", 16, 1);
  auto w = std::make_unique<TelemetryWriter>(cfg);
  w->push(counter_sample(0));
  TelemetryReader r(cfg.shm_name, TelemetryReader::Start::oldest);
  w.reset();  // unlinks; our mapping stays valid
  EXPECT_TRUE(r.writer_closed());
  std::vector<TelemetryRecord> out(4);
  EXPECT_EQ(r.read(out).count, 1u);
  EXPECT_THROW(TelemetryReader(cfg.shm_name), std::runtime_error) << "the name is gone";
}

TEST(Telemetry, ReaderRefusesForeignOrNewerLayouts) {
  EXPECT_THROW(TelemetryReader("/knoblab-test-no-such-ring"), std::runtime_error);

  const std::string junk = unique_shm_name("junk");
  const int fd = ::shm_open(junk.c_str(), O_CREAT | O_RDWR, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 4096), 0);
  ASSERT_EQ(::write(fd, "not a ring", 10), 10);
  ::close(fd);
  EXPECT_THROW(TelemetryReader{junk}, std::runtime_error);
  ::shm_unlink(junk.c_str());

  const auto cfg = config_for("version", 16, 1);
  TelemetryWriter w(cfg);
  const int wfd = ::shm_open(cfg.shm_name.c_str(), O_RDWR, 0);
  ASSERT_GE(wfd, 0);
  void* p = ::mmap(nullptr, sizeof(telemetry::Header), PROT_READ | PROT_WRITE, MAP_SHARED, wfd, 0);
  ::close(wfd);
  ASSERT_NE(p, MAP_FAILED);
  static_cast<telemetry::Header*>(p)->layout_version = 2;
  try {
    TelemetryReader r(cfg.shm_name);
    FAIL() << "accepted layout version 2";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("layout version 2"), std::string::npos) << e.what();
  }
  ::munmap(p, sizeof(telemetry::Header));
}

TEST(Telemetry, WriterRefusesBadConfig) {
  EXPECT_THROW(TelemetryWriter(config_for("cap", 100, 1)), std::runtime_error);
  EXPECT_THROW(TelemetryWriter(config_for("dec", 16, 0)), std::runtime_error);
  auto c = config_for("grp", 16, 1);
  c.group = "no-such-group-knoblab";
  EXPECT_THROW(TelemetryWriter{c}, std::runtime_error);
  c = config_for("name", 16, 1);
  c.shm_name = "no-leading-slash";
  EXPECT_THROW(TelemetryWriter{c}, std::runtime_error);
}

TEST(Telemetry, WriterReplacesALeftoverRing) {
  const auto cfg = config_for("leftover", 16, 1);
  const int fd = ::shm_open(cfg.shm_name.c_str(), O_CREAT | O_RDWR, 0600);  // a dead daemon's
  ASSERT_GE(fd, 0);
  ::close(fd);
  TelemetryWriter w(cfg);
  w.push(counter_sample(0));
  TelemetryReader r(cfg.shm_name, TelemetryReader::Start::oldest);
  std::vector<TelemetryRecord> out(2);
  EXPECT_EQ(r.read(out).count, 1u);
}

// A second daemon started by mistake once unlinked the running one's ring
// (readers then failed with "shm_open: No such file"): a ring whose writer
// lives is refused and left as it was.
TEST(Telemetry, ASecondWriterRefusesARingWhoseWriterIsAliveAndLeavesItAlone) {
  const auto cfg = config_for("alive", 16, 1);
  TelemetryWriter first(cfg);
  first.push(counter_sample(0));
  try {
    TelemetryWriter second(cfg);
    FAIL() << "a second writer took a live ring";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("in use by a running daemon"), std::string::npos) << e.what();
  }
  first.push(counter_sample(1));
  TelemetryReader r(cfg.shm_name, TelemetryReader::Start::oldest);
  std::vector<TelemetryRecord> out(4);
  EXPECT_EQ(r.read(out).count, 2u);  // the first writer's ring, both records
}

// Writer and readers at full speed on a tiny ring for 0.4 s: overruns happen
// all the time, torn records never, and every record is read or counted lost.
TEST(Telemetry, ConcurrentWriterAndReadersNeverTear) {
  constexpr std::uint32_t kDecimation = 2;
  const auto cfg = config_for("threads", 16, kDecimation);
  TelemetryWriter w(cfg);
  std::atomic<bool> done{false};

  struct Tally {
    std::atomic<std::uint64_t> read{0};
    std::uint64_t lost = 0, torn = 0, gaps = 0;
  };
  auto reader = [&](TelemetryReader& r, Tally& tally) {
    std::vector<TelemetryRecord> out(7);  // small reads: more interleaving
    std::uint64_t expected = 0;
    for (;;) {
      const bool finished = done.load();
      const auto res = r.read(out);
      if (res.first_sequence != expected + res.lost) ++tally.gaps;
      expected = res.first_sequence + res.count;
      tally.read += res.count;
      tally.lost += res.lost;
      for (std::size_t k = 0; k < res.count; ++k) {
        if (!consistent(out[k], kDecimation)) ++tally.torn;
        // the record's own counter must match its sequence
        if (static_cast<std::uint64_t>(out[k].t) != (res.first_sequence + k + 1) * kDecimation - 1) ++tally.gaps;
      }
      if (finished && res.count == 0) break;
    }
  };
  Tally t1, t2;
  TelemetryReader a(cfg.shm_name, TelemetryReader::Start::oldest), b(cfg.shm_name, TelemetryReader::Start::oldest);
  std::thread r1(reader, std::ref(a), std::ref(t1)), r2(reader, std::ref(b), std::ref(t2));
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(400);
  std::uint64_t i = 0;
  while (std::chrono::steady_clock::now() < until) {
    for (std::uint64_t end = i + 2'000; i < end; ++i) w.push(counter_sample(i));  // ~60 laps
    std::this_thread::yield();  // on few cores, let both readers run too
  }
  done = true;
  r1.join();
  r2.join();
  const std::uint64_t records = w.records_published();
  for (const Tally* t : {&t1, &t2}) {
    EXPECT_EQ(t->torn, 0u);
    EXPECT_EQ(t->gaps, 0u);
    EXPECT_EQ(t->read + t->lost, records) << "every record is either read or counted lost";
    EXPECT_GE(t->read, 16u) << "the readers hardly ran";
    EXPECT_GT(t->lost, 0u) << "a 16-slot ring at full speed must overrun";
  }
  std::printf("[          ] %llu records; reader 1: %llu read, %llu lost; reader 2: %llu read, %llu lost\n",
              static_cast<unsigned long long>(records), static_cast<unsigned long long>(t1.read.load()),
              static_cast<unsigned long long>(t1.lost), static_cast<unsigned long long>(t2.read.load()),
              static_cast<unsigned long long>(t2.lost));
}

}  // namespace
}  // namespace knoblab::control::test
