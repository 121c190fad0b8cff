// Ctrl-C and SIGTERM during a long command, as a person at a terminal sends
// them: the real knoblab runs on a pseudo-terminal, the test waits until its
// progress line shows the work under way, signals it, and checks that it
// ends with status 130 saying "cancelled", with the store intact and no
// result, partial row or file left anywhere.
#include <gtest/gtest.h>
#include <signal.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <thread>

#include <filesystem>
#include <string>
#include <vector>

#include "knoblab/store/store.hpp"
#include "process.hpp"
#include "terminal.hpp"

namespace knoblab::test {
namespace {

std::int64_t rows(const std::string& db, const std::string& table) {
  return store::Store::open(db).connection().query_int("SELECT count(*) FROM " + table);
}

bool empty_dir(const std::filesystem::path& dir) {
  return std::filesystem::is_empty(dir);
}

class CancelCli : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = (dir_ / "k.db").string();
    std::filesystem::create_directories(tmp_);
  }
  // A capture of `seconds` in the store (capture 1); a long one sweeps
  // slower, to stay under the velocity limit.
  void capture(const std::string& seconds, bool slow) {
    std::vector<std::string> args = {"simulate", "--knob", "moderate-detents", "--seconds", seconds, "--db", db_};
    if (slow) args.insert(args.end(), {"--sweep", "0,90,1,60"});
    const RunResult r = run_knoblab(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }

  ScratchDir dir_;
  std::string db_;
  std::filesystem::path tmp_ = dir_ / "tmp";  // the command's TMPDIR: its scratch files
};

TEST_F(CancelCli, CtrlCDuringADiscrepancyExits130AndStoresAndWritesNothing) {
  capture("8", false);
  const auto report = dir_ / "report";
  const auto json = dir_ / "r.json";
  TerminalRun run({"discrepancy", "--capture", "1", "--db", db_, "--report", report.string(), "--json",
                   json.string()},
                  tmp_);
  ASSERT_TRUE(run.wait_for("knoblab discrepancy: trying candidates, round 1: 2 of")) << run.output();
  ::kill(run.pid(), SIGINT);
  EXPECT_EQ(run.finish(), 130) << run.output();
  EXPECT_NE(run.output().find("knoblab discrepancy: cancelled"), std::string::npos) << run.output();
  EXPECT_EQ(run.output().find("stored as"), std::string::npos) << run.output();

  auto store = store::Store::open(db_);
  EXPECT_EQ(store.integrity_check(), "ok");
  EXPECT_EQ(rows(db_, "discrepancies"), 0);
  EXPECT_EQ(rows(db_, "discrepancy_files"), 0);
  EXPECT_EQ(rows(db_, "captures"), 1);  // the capture analysed stays
  EXPECT_FALSE(std::filesystem::exists(report));
  EXPECT_FALSE(std::filesystem::exists(json));
  EXPECT_TRUE(empty_dir(tmp_));
  for (const auto& e : std::filesystem::directory_iterator(dir_.path()))  // no temporary either
    EXPECT_TRUE(e.path().filename().string().starts_with("k.db") || e.path() == tmp_) << e.path();
}

TEST_F(CancelCli, SigtermDuringAFitExits130AndStoresAndWritesNothing) {
  capture("60", true);  // 300 000 samples: the fit runs long enough to be caught
  const auto report = dir_ / "report";
  TerminalRun run({"fit", "--capture", "1", "--db", db_, "--report", report.string(), "--render-model",
                   (dir_ / "model.json").string()},
                  tmp_);
  ASSERT_TRUE(run.wait_for("knoblab fit: preparing")) << run.output();
  ::kill(run.pid(), SIGTERM);
  EXPECT_EQ(run.finish(), 130) << run.output();
  EXPECT_NE(run.output().find("knoblab fit: cancelled"), std::string::npos) << run.output();
  EXPECT_EQ(store::Store::open(db_).integrity_check(), "ok");
  EXPECT_EQ(rows(db_, "fits"), 0);
  EXPECT_EQ(rows(db_, "fit_files"), 0);
  EXPECT_FALSE(std::filesystem::exists(report));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "model.json"));
  EXPECT_TRUE(empty_dir(tmp_));
}

TEST_F(CancelCli, CtrlCWhileAFitDrawsItsReportLeavesNoReportFileAndNoFit) {
  capture("10", false);
  const auto report = dir_ / "report";
  TerminalRun run({"fit", "--capture", "1", "--db", db_, "--report", report.string()}, tmp_);
  ASSERT_TRUE(run.wait_for("knoblab fit: drawing the report: 1 of 4")) << run.output();
  ::kill(run.pid(), SIGINT);
  EXPECT_EQ(run.finish(), 130) << run.output();
  EXPECT_NE(run.output().find("knoblab fit: cancelled"), std::string::npos) << run.output();
  // Stopped before the next figure, not after all four.
  EXPECT_EQ(run.output().find("drawing the report: 3 of 4"), std::string::npos) << run.output();
  EXPECT_EQ(rows(db_, "fits"), 0);
  EXPECT_FALSE(std::filesystem::exists(report));
  EXPECT_TRUE(empty_dir(tmp_));  // the files drawn so far went with the scratch directory
}

TEST_F(CancelCli, CtrlCDuringASimulationKeepsNoCaptureAndWritesNoCsv) {
  const auto csv = dir_ / "k.csv";
  TerminalRun run({"simulate", "--knob", "moderate-detents", "--seconds", "120", "--sweep", "0,90,1,60", "--db",
                   db_, "--out", csv.string()},
                  tmp_);
  ASSERT_TRUE(run.wait_for("knoblab simulate: simulating: 1 %")) << run.output();
  ::kill(run.pid(), SIGINT);
  EXPECT_EQ(run.finish(), 130) << run.output();
  EXPECT_NE(run.output().find("knoblab simulate: cancelled"), std::string::npos) << run.output();
  auto store = store::Store::open(db_);
  EXPECT_EQ(store.integrity_check(), "ok");
  // Batches of it had been committed; they are gone, with the knob made for it.
  EXPECT_EQ(rows(db_, "captures"), 0);
  EXPECT_EQ(rows(db_, "samples"), 0);
  EXPECT_EQ(rows(db_, "knobs"), 0);
  EXPECT_FALSE(std::filesystem::exists(csv));
  for (const auto& e : std::filesystem::directory_iterator(dir_.path()))  // no temporary either
    EXPECT_TRUE(e.path().filename().string().starts_with("k.db") || e.path() == tmp_) << e.path();
}

TEST_F(CancelCli, CtrlCDuringAnImportTakesItsSamplesOutAgain) {
  const auto csv = dir_ / "big.csv";
  const RunResult made = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "60", "--sweep",
                                      "0,90,1,60", "--out", csv.string()});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "subtle-detents", "--seconds", "1", "--db", db_}).exit_code, 0);
  const std::string before = [&] {
    auto s = store::Store::open(db_);
    return std::to_string(s.list_captures().size()) + " " + std::to_string(rows(db_, "samples"));
  }();
  TerminalRun run({"import", csv.string(), "--db", db_}, tmp_);
  ASSERT_TRUE(run.wait_for("knoblab import: importing: ")) << run.output();
  ::kill(run.pid(), SIGINT);
  EXPECT_EQ(run.finish(), 130) << run.output();
  EXPECT_NE(run.output().find("knoblab import: cancelled"), std::string::npos) << run.output();
  EXPECT_EQ(store::Store::open(db_).integrity_check(), "ok");
  EXPECT_EQ(std::to_string(store::Store::open(db_).list_captures().size()) + " " +
                std::to_string(rows(db_, "samples")),
            before);
}

TEST_F(CancelCli, CtrlCDuringTheDemoKeepsTheKnobsDoneWholeAndTheCaptureUnderWayNot) {
  TerminalRun run({"demo", "--db", db_, "--seconds", "2"}, tmp_);
  // The first knob done (its capture, fit, discovery capture), the second under way.
  ASSERT_TRUE(run.wait_for("knoblab demo: high-inertia: simulating")) << run.output();
  ::kill(run.pid(), SIGINT);
  EXPECT_EQ(run.finish(), 130) << run.output();
  EXPECT_NE(run.output().find("knoblab demo: cancelled"), std::string::npos) << run.output();
  EXPECT_NE(run.output().find("high-friction: capture 1"), std::string::npos) << run.output();
  EXPECT_EQ(store::Store::open(db_).integrity_check(), "ok");
  EXPECT_EQ(rows(db_, "captures"), 2) << "high-friction's two captures, nothing of high-inertia's";
  EXPECT_EQ(store::Store::open(db_).connection().query_int("SELECT count(*) FROM captures WHERE status != 'complete'"), 0);
  EXPECT_EQ(rows(db_, "fits"), 1);
}

// The input is a FIFO the test writes, as a slow disk or network share would
// deliver a big file: Ctrl-C comes while convert is still reading it.
//
// convert opens the input twice: first to tell a CSV from an array file by
// its first bytes, then, once it says it is reading, to read it. On a busy
// host its second open can meet the test's first stream before that one is
// closed: convert then reads that stream's short file whole and the test's
// second stream waits for a reader that never comes. That once hung ctest
// for good. Now a reader end the test opens releases such a stream on every
// path, and a run where convert did not meet the second stream proves
// nothing, so it is tried again (three times at most).
TEST_F(CancelCli, CtrlCWhileAConvertReadsItsInputWritesNoOutput) {
  const auto out = dir_ / "out.csv";
  const std::string header = "time_ms,angle_deg,torque_mNm\n";
  std::string body;
  for (int i = 0; i < 2000; ++i) body += std::to_string(i) + "," + std::to_string(i % 360) + ",1.5\n";
  const auto wait = [](const std::atomic<bool>& flag) {
    for (int i = 0; i < 6000 && !flag; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  };
  for (int attempt = 1;; ++attempt) {
    const std::string fifo = (dir_ / ("slow-" + std::to_string(attempt) + ".csv")).string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::atomic<bool> reading{false}, half_written{false}, signalled{false};
    std::thread writer([&] {
      { std::ofstream(fifo, std::ios::binary) << header << "0,0,1.5\n"; }
      wait(reading);
      std::ofstream f(fifo, std::ios::binary);
      f << header << body.substr(0, body.size() / 2) << std::flush;
      half_written = true;
      wait(signalled);
      f << body.substr(body.size() / 2);
    });
    TerminalRun run({"convert", fifo, out.string(), "--columns", "time_ms=t:ms,angle_deg=theta:deg,torque_mNm=torque:mN*m"},
                    tmp_);
    reading = run.wait_for("knoblab convert: reading");
    wait(half_written);
    const bool mid_read = half_written;  // convert holds the second stream, half of it written
    ::kill(run.pid(), SIGINT);
    signalled = true;
    // Never read from: it only lets a stream still waiting for a reader open.
    const int unblock = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    writer.join();
    if (unblock >= 0) ::close(unblock);
    const int status = run.finish();
    std::filesystem::remove(fifo);
    if (!mid_read && attempt < 3) {
      std::filesystem::remove(out);
      continue;
    }
    ASSERT_TRUE(reading) << run.output();
    ASSERT_TRUE(mid_read) << "convert never read the second stream in " << attempt << " runs\n" << run.output();
    EXPECT_EQ(status, 130) << run.output();
    EXPECT_NE(run.output().find("knoblab convert: cancelled"), std::string::npos) << run.output();
    EXPECT_FALSE(std::filesystem::exists(out));
    for (const auto& e : std::filesystem::directory_iterator(dir_.path()))  // no temporary either
      EXPECT_TRUE(e.path() == tmp_) << e.path();
    break;
  }
}

}  // namespace
}  // namespace knoblab::test
