// The daemon recording into a store that other processes use too: another
// writer holding the lock for longer than any busy timeout, a store that
// cannot take a capture at all, and a large import beside a capture while a
// reader lists.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <string>
#include <thread>
#include <unistd.h>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/control/telemetry_reader.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/sim/presets.hpp"
#include "knoblab/store/store.hpp"
#include "shared_host.hpp"
#include "held_commit.hpp"
#include "temp_db.hpp"

namespace knoblab::hapticd {
namespace {

using ::testing::StartsWith;
using Clock = std::chrono::steady_clock;

using testing::HeldCommit;
using testing::TempDb;

// The daemon at 10 kHz on the sim backend, its loop on a thread.
struct Rig {
  hal::MemoryLines* lines = nullptr;  // owned by the daemon
  std::unique_ptr<Daemon> daemon;
  std::thread loop;
  rt::LoopResult timing;

  explicit Rig(const std::filesystem::path& db, RecorderOptions recorder = {}, std::string telemetry_shm = "") {
    sim::PlantConfig plant;
    plant.knob = *sim::presets::knob("moderate-detents");
    auto daq = std::make_unique<capture::SimDaq>(plant, 10000.0);
    DaemonConfig cfg;
    cfg.core.rate_hz = 10000.0;
    cfg.core.calibration = daq->calibration();
    cfg.db = db;
    cfg.knob = "moderate-detents";
    cfg.recorder = std::move(recorder);
    cfg.telemetry_shm = std::move(telemetry_shm);
    shared_host::configure(cfg);
    auto l = std::make_unique<hal::MemoryLines>(false);
    lines = l.get();
    daemon = std::make_unique<Daemon>(cfg, std::move(daq), std::move(l));
    loop = std::thread([this] { timing = daemon->run(); });
  }
  ~Rig() {
    daemon->stop();
    loop.join();
    shared_host::report_timing(timing);
  }
  std::vector<FinishedRecording> wait_finished(std::chrono::seconds timeout) {
    const auto end = Clock::now() + timeout;
    while (Clock::now() < end) {
      auto f = daemon->finished();
      if (!f.empty()) return f;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return {};
  }
  // The loop is no longer recording (the capture's last cycle has run).
  bool wait_capture_over(std::chrono::seconds timeout) {
    const auto end = Clock::now() + timeout;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let the command land
    while (Clock::now() < end) {
      const CoreState s = daemon->core().state();
      if (s.recording_id == 0 && s.mode == Mode::Idle) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
};

void print_stats(const char* what, const RecorderStats& s) {
  std::printf("[ figures  ] %s: recorder buffered at most %llu samples (%.2f s at 10 kHz), "
              "%llu busy retries, %llu recordings cut\n",
              what, static_cast<unsigned long long>(s.max_buffered),
              static_cast<double>(s.max_buffered) / 10000.0, static_cast<unsigned long long>(s.retries),
              static_cast<unsigned long long>(s.failed));
}

// Another connection holds the write lock for 7 s - longer than the 5 s any
// store connection waits - while a 2 s capture runs: the writer thread keeps
// draining the ring, the recorder keeps the samples, and all of them are
// stored once the lock is gone.
TEST(DaemonStore, EverySampleIsKeptWhileAnotherWriterHoldsTheStoreLongerThanTheBusyTimeout) {
  TempDb db{"contention"};
  { store::Store::open(db.path()); }
  std::vector<FinishedRecording> f;
  RecorderStats stats;
  {
    Rig rig(db.path());
    auto other = store::sqlite::Connection::open(db.path());
    other.exec("BEGIN IMMEDIATE");
    const auto locked = Clock::now();
    capture::CaptureConfig cc;
    std::string why;
    ASSERT_TRUE(rig.daemon->start_capture(cc, 2.0, "moderate-detents", why)) << why;
    ASSERT_TRUE(rig.wait_capture_over(std::chrono::seconds(30)));
    std::this_thread::sleep_until(locked + std::chrono::seconds(7));
    EXPECT_TRUE(rig.daemon->finished().empty()) << "stored while the lock was held?";
    EXPECT_EQ(rig.daemon->core().state().faults, 0u);
    EXPECT_EQ(rig.daemon->recorder_stats().buffered, 20000u);
    other.exec("COMMIT");
    f = rig.wait_finished(std::chrono::seconds(30));
    stats = rig.daemon->recorder_stats();
  }
  print_stats("lock held 7 s", stats);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_TRUE(f[0].complete) << f[0].end_reason;
  EXPECT_EQ(f[0].samples, 20000);
  EXPECT_GT(stats.retries, 0u);
  EXPECT_EQ(stats.max_buffered, 20000u);
  EXPECT_EQ(stats.buffered, 0u);
  store::Store s = store::Store::open(db.path());
  const auto info = s.capture_info(f[0].capture_id);
  EXPECT_EQ(info->status, "complete");
  EXPECT_EQ(info->sample_count, 20000);
  const interchange::Capture c = s.load_samples(f[0].capture_id);
  ASSERT_EQ(c.size(), 20000u);
  for (std::size_t i = 0; i < c.size(); ++i) ASSERT_EQ(c.t[i], static_cast<double>(i) * (1.0 / 10000.0));
}

// A disk whose commit takes as long as the test holds it (an SD card's or
// an emulated disk's fsync can take seconds): while the store thread waits
// inside it, the loop's telemetry keeps coming and the ring keeps draining.
// Were the ring drained by the thread that commits, the telemetry would stop
// until the commit returns, and the reader below would wait in vain.
TEST(DaemonStore, TelemetryFlowsAndTheRingDrainsWhileACommitWaitsForTheDisk) {
  TempDb db{"contention"};
  { store::Store::open(db.path()); }
  HeldCommit disk;
  const std::string shm = "/knoblab-store-test-" + std::to_string(::getpid());
  std::vector<FinishedRecording> f;
  double telemetry_during_commit_s = 0.0;
  std::uint64_t dropped = 0;
  {
    Rig rig(db.path(), disk.options(), shm);
    capture::CaptureConfig cc;
    std::string why;
    ASSERT_TRUE(rig.daemon->start_capture(cc, 2.0, "moderate-detents", why)) << why;
    const bool in_commit = disk.wait_entered(std::chrono::seconds(30));
    // One second of the loop's telemetry, read while the commit is held.
    control::TelemetryReader reader(shm);
    std::vector<control::TelemetryRecord> buf(256);
    std::optional<double> t0;
    const auto give_up = Clock::now() + std::chrono::seconds(30);
    while (in_commit && telemetry_during_commit_s < 1.0 && Clock::now() < give_up) {
      const auto r = reader.read(buf);
      for (std::size_t i = 0; i < r.count; ++i) {
        if (!t0) t0 = buf[i].t;
        telemetry_during_commit_s = buf[i].t - *t0;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    const bool still_in_commit = rig.daemon->finished().empty();
    disk.release();
    EXPECT_TRUE(in_commit) << "the capture was never committed";
    EXPECT_TRUE(still_in_commit);
    f = rig.wait_finished(std::chrono::seconds(30));
    dropped = rig.daemon->ring_dropped();
  }
  std::printf("[ figures  ] telemetry read while a commit was held: %.2f s of the loop's\n",
              telemetry_during_commit_s);
  EXPECT_GE(telemetry_during_commit_s, 1.0) << "telemetry stopped while the store committed";
  EXPECT_EQ(dropped, 0u);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_TRUE(f[0].complete) << f[0].end_reason;
  EXPECT_EQ(f[0].samples, 20000);
  store::Store s = store::Store::open(db.path());
  EXPECT_EQ(s.capture_info(f[0].capture_id)->sample_count, 20000);
}

// A store that stays locked past what the recorder may hold: the capture is
// stopped, the motor made safe (fault 'recording'), and what was held is
// stored marked incomplete with the reason.
TEST(DaemonStore, ACaptureTheStoreCannotTakeIsStoppedAndTheMotorMadeSafe) {
  TempDb db{"contention"};
  { store::Store::open(db.path()); }
  std::vector<FinishedRecording> f;
  {
    RecorderOptions small;
    small.max_buffered = 5000;  // half a second at 10 kHz
    Rig rig(db.path(), small);
    auto other = store::sqlite::Connection::open(db.path());
    other.exec("BEGIN IMMEDIATE");
    capture::CaptureConfig cc;
    std::string why;
    ASSERT_TRUE(rig.daemon->start_capture(cc, 5.0, "moderate-detents", why)) << why;
    // The capture drives the motor until the recorder gives up on it.
    std::uint32_t faults = 0;
    for (int i = 0; i < 1000 && !(faults & kFaultRecording); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      faults = rig.daemon->core().state().faults;
    }
    ASSERT_TRUE(faults & kFaultRecording) << "faults " << fault_list(faults);
    ASSERT_TRUE(rig.wait_capture_over(std::chrono::seconds(5))) << "the capture went on";
    EXPECT_FALSE(rig.lines->amp_enable());
    EXPECT_EQ(rig.daemon->recorder_stats().failed, 1u);
    other.exec("COMMIT");
    f = rig.wait_finished(std::chrono::seconds(30));
  }
  ASSERT_EQ(f.size(), 1u);
  EXPECT_FALSE(f[0].complete);
  EXPECT_THAT(f[0].end_reason, StartsWith("store busy"));
  EXPECT_EQ(f[0].samples, 5000);
  store::Store s = store::Store::open(db.path());
  const auto info = s.capture_info(f[0].capture_id);
  EXPECT_EQ(info->status, "incomplete");
  EXPECT_EQ(info->end_reason, f[0].end_reason);
  EXPECT_EQ(info->sample_count, 5000);
}

// Acceptance: a capture runs while a 200 000-row CSV is imported into the
// same store and a reader lists it over and over: every sample the capture
// promised is stored, complete, and the reader answers throughout.
TEST(DaemonStore, ALargeImportBesideACaptureLosesNoSampleAndListingAnswersThroughout) {
  constexpr std::size_t kRows = 200'000;
  constexpr double kSeconds = 5.0;
  TempDb db{"contention"};
  {
    interchange::Capture big;
    big.metadata = {{"knob", "imported"}};
    for (std::size_t i = 0; i < kRows; ++i) {
      const double t = static_cast<double>(i) * 1e-4;
      big.t.push_back(t);
      big.theta.push_back(std::sin(t));
      big.omega.push_back(std::cos(t));
      big.alpha.push_back(-std::sin(t));
      big.torque.push_back(0.01 * std::cos(3 * t));
    }
    interchange::write_csv(big, db.dir / "big.csv");
  }
  { store::Store::open(db.path()); }
  // Parsed up front, so the import starts writing as soon as it is started.
  const interchange::Capture csv = interchange::read_csv(db.dir / "big.csv");
  ASSERT_EQ(csv.size(), kRows);

  // The reader: `knoblab list` over and over, as another process would.
  std::atomic<bool> stop_reading{false};
  std::atomic<int> answers{0}, answers_during_import{0}, answers_during_both{0}, read_errors{0};
  std::atomic<bool> capture_recording{false};
  std::string read_error;
  double slowest_list_ms = 0;
  std::thread reader([&] {
    while (!stop_reading) {
      const auto t0 = Clock::now();
      try {
        store::OpenOptions ro;
        ro.read_only = true;
        store::Store s = store::Store::open(db.path(), ro);
        bool importing = false, capturing = false;
        for (const auto& c : s.list_captures()) {
          if (c.source == "import" && c.status == "recording") importing = true;
          if (c.source == "hapticd" && c.status == "recording") capturing = true;
        }
        slowest_list_ms = std::max(slowest_list_ms, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        ++answers;
        if (capturing) capture_recording = true;
        if (importing) ++answers_during_import;
        if (importing && capturing) ++answers_during_both;
      } catch (const std::exception& e) {
        if (read_errors++ == 0) read_error = e.what();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });

  std::vector<FinishedRecording> f;
  RecorderStats stats;
  std::int64_t import_id = 0, import_commits = 0;
  double longest_commit_gap_ms = 0;
  bool import_outlasted_capture = false;
  std::atomic<bool> import_done{false};
  std::string import_error;
  {
    Rig rig(db.path());
    capture::CaptureConfig cc;
    std::string why;
    ASSERT_TRUE(rig.daemon->start_capture(cc, kSeconds, "moderate-detents", why)) << why;
    // The import starts once the capture is on its way into the store.
    for (int i = 0; i < 500 && !capture_recording; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(capture_recording) << "the capture never showed as recording";
    std::thread importer([&] {
      try {
        store::Store s = store::Store::open(db.path());
        store::ImportOptions options;
        auto last = Clock::now();
        options.on_commit = [&](std::int64_t) {
          const auto now = Clock::now();
          longest_commit_gap_ms = std::max(longest_commit_gap_ms, std::chrono::duration<double, std::milli>(now - last).count());
          last = now;
          ++import_commits;
        };
        store::NewCapture info;
        info.knob = "imported";
        import_id = s.import_capture(csv, info, options);
      } catch (const std::exception& e) {
        import_error = e.what();
      }
      import_done = true;
    });
    f = rig.wait_finished(std::chrono::seconds(60));
    import_outlasted_capture = !import_done;
    importer.join();
    stats = rig.daemon->recorder_stats();
  }
  stop_reading = true;
  reader.join();

  print_stats("beside the import", stats);
  std::printf("[ figures  ] import of %zu rows: %lld commits, longest commit-to-commit %.1f ms; "
              "%s; reader: %d answers (%d during the import, %d during both), slowest %.1f ms\n",
              kRows, static_cast<long long>(import_commits), longest_commit_gap_ms,
              import_outlasted_capture ? "still importing when the capture was stored"
                                       : "done before the capture was stored",
              answers.load(), answers_during_import.load(), answers_during_both.load(), slowest_list_ms);

  ASSERT_EQ(import_error, "");
  ASSERT_EQ(f.size(), 1u);
  const std::int64_t promised = std::llround(kSeconds * 10000.0);
  EXPECT_TRUE(f[0].complete) << f[0].end_reason;
  EXPECT_EQ(f[0].samples, promised);
  EXPECT_EQ(stats.failed, 0u);
  EXPECT_EQ(read_errors.load(), 0) << read_error;
  EXPECT_GT(answers_during_import.load(), 0) << "the reader never answered while the import ran";
  EXPECT_GT(answers_during_both.load(), 0) << "the reader never answered while both wrote";

  store::Store s = store::Store::open(db.path());
  const auto cap = s.capture_info(f[0].capture_id);
  EXPECT_EQ(cap->status, "complete");
  EXPECT_EQ(cap->sample_count, promised);
  const interchange::Capture c = s.load_samples(f[0].capture_id);
  ASSERT_EQ(c.size(), static_cast<std::size_t>(promised));
  for (std::size_t i = 0; i < c.size(); ++i) ASSERT_EQ(c.t[i], static_cast<double>(i) * (1.0 / 10000.0));
  const auto imported = s.capture_info(import_id);
  EXPECT_EQ(imported->status, "complete");
  EXPECT_EQ(imported->sample_count, static_cast<std::int64_t>(kRows));
}

}  // namespace
}  // namespace knoblab::hapticd
