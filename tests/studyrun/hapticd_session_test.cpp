// Studies run end to end through the real hapticd on the sim backend:
// `knoblab study simulate` steers the simulated knob through hapticd's guided
// hand, hapticd records each trial with the biometrics box
// (knoblab-modbus-sim over Modbus TCP), and every trial lands in the store.
// Then the power-cut case: knoblab and hapticd killed mid-session, both
// started again, and the session resumes at the trial that was running.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <future>
#include <string>
#include <thread>

#include "knoblab/store/store.hpp"
#include "knoblab/studyrun/hapticd_apparatus.hpp"
#include "process.hpp"
#include "protocols.hpp"

namespace knoblab::test {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;

class Rig {
 public:
  Rig() {
    box_ = spawn({KNOBLAB_MODBUS_SIM_PATH, "--port", "0"}, (dir_ / "box.out").string(), (dir_ / "box.err").string());
    EXPECT_GT(box_, 0);
    EXPECT_TRUE(eventually([&] {
      const std::string out = read_file(dir_ / "box.out");
      const auto colon = out.rfind(':');
      if (out.find("listening") == std::string::npos || colon == std::string::npos) return false;
      port_ = std::stoi(out.substr(colon + 1));
      return true;
    })) << read_file(dir_ / "box.err");
    const json config = {
        {"daq", {{"backend", "sim"}, {"knob", "study3-not-rendered"}, {"rate_hz", 5000}, {"hand", {{"channel", hand()}}}}},
        {"lines", {{"backend", "memory"}, {"estop", "released"}}},
        {"modbus",
         {{"biometrics", {{"transport", "tcp"}, {"host", "127.0.0.1"}, {"port", port_}, {"unit", 2}}},
          {"biometrics_timeout_ms", 400}}}};
    write_file(dir_ / "hapticd.json", config.dump(2));
    start_hapticd();
  }
  ~Rig() {
    stop_hapticd(SIGTERM);
    if (box_ > 0) ::kill(box_, SIGTERM), wait_exit(box_, 5s);
    ::shm_unlink(hand().c_str());
    ::shm_unlink(telemetry().c_str());
  }
  void start_hapticd() {
    hapticd_ = spawn({KNOBLAB_HAPTICD_PATH, "--config", (dir_ / "hapticd.json").string(), "--rate", "5000", "--socket",
                      socket(), "--db", db(), "--telemetry", telemetry(), "--max-overruns", "1000000"},
                     (dir_ / "hapticd.out").string(), (dir_ / "hapticd.err").string());
    ASSERT_GT(hapticd_, 0);
    ASSERT_TRUE(eventually([&] { return run_knoblab({"ctl", "--socket", socket(), "get_state"}).exit_code == 0; }))
        << log();
  }
  void stop_hapticd(int sig) {
    if (hapticd_ <= 0) return;
    ::kill(hapticd_, sig);
    wait_exit(hapticd_, 10s);
    hapticd_ = -1;
  }
  std::vector<std::string> simulate(const std::string& protocol_file, const std::string& participants = "1") const {
    return {"study", "simulate", protocol_file, "--participants", participants, "--db", db(), "--socket", socket(),
            "--hand", hand()};
  }
  std::string write_protocol(const json& p) const {
    const auto path = dir_ / (p["study"].get<std::string>() + ".json");
    write_file(path, p.dump(2));
    return path.string();
  }
  std::string socket() const { return (dir_ / "h.sock").string(); }
  std::string db() const { return (dir_ / "lab.sqlite").string(); }
  std::string hand() const { return "/knoblab-test-hand-" + std::to_string(::getpid()); }
  std::string telemetry() const { return "/knoblab-test-tlm-" + std::to_string(::getpid()); }
  std::string log() const { return read_file(dir_ / "hapticd.err"); }
  pid_t hapticd_pid() const { return hapticd_; }
  const ScratchDir& dir() const { return dir_; }

 private:
  ScratchDir dir_;
  pid_t box_ = -1, hapticd_ = -1;
  int port_ = 0;
};

std::vector<store::StudyTrial> trials_of(const std::string& db, const std::string& study) {
  store::Store s = store::Store::open(db, {.read_only = true});
  std::vector<store::StudyTrial> all;
  for (const auto& session : s.study_sessions(study)) {
    auto t = s.study_trials(session.session_id);
    all.insert(all.end(), t.begin(), t.end());
  }
  return all;
}

// Every trial has its recording in the store, with samples and the box's
// biometrics, and scores from them.
void expect_recorded(const std::string& db, const std::vector<store::StudyTrial>& trials, bool biometrics) {
  store::Store s = store::Store::open(db, {.read_only = true});
  for (const store::StudyTrial& t : trials) {
    ASSERT_TRUE(t.capture_id) << "trial " << t.trial_index;
    const auto info = s.capture_info(*t.capture_id);
    ASSERT_TRUE(info);
    EXPECT_GT(s.load_samples(*t.capture_id).t.size(), 1000u);
    const json bio = json::parse(t.biometrics_json);
    EXPECT_LT(bio["onset_s"].get<double>(), bio["end_s"].get<double>());
    if (!biometrics) continue;  // the matching study recorded none
    EXPECT_GT(s.load_biometrics(*t.capture_id).size(), 32u) << "the box samples at 32 Hz";
    ASSERT_TRUE(bio.contains("score")) << t.biometrics_json;
    EXPECT_TRUE(bio["score"]["emg_V"].is_number()) << t.biometrics_json;
    EXPECT_TRUE(bio["score"]["sc_S"].is_number()) << t.biometrics_json;
    EXPECT_GE(bio["score"]["baseline_samples"].get<int>(), 32) << "a baseline of at least a second";
  }
}

TEST(StudyThroughHapticd, ShortenedPointingMatchingAndListSelectionRunEndToEndWithEveryTrialStored) {
  Rig rig;
  struct Case {
    json protocol;
    std::size_t trials;
    const char* scale;
  };
  for (const Case& c : {Case{shortened_pointing_json(), 4, "appropriateness"},
                        Case{shortened_matching_json(), 2, "satisfaction"},
                        Case{shortened_list_json(), 4, "sam_valence"}}) {
    const std::string study = c.protocol["study"];
    const RunResult r = run_knoblab(rig.simulate(rig.write_protocol(c.protocol)));
    ASSERT_EQ(r.exit_code, 0) << study << "\n" << r.out << r.err << rig.log();
    EXPECT_NE(r.out.find("SIM01: session"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("finished"), std::string::npos) << r.out;
    const auto trials = trials_of(rig.db(), study);
    ASSERT_EQ(trials.size(), c.trials) << study;
    for (const auto& t : trials) {
      EXPECT_TRUE(json::parse(t.ratings_json).contains(c.scale)) << t.ratings_json;
      EXPECT_GT(t.ended_unix, t.started_unix);
      EXPECT_FALSE(json::parse(t.condition_json).empty());
    }
    expect_recorded(rig.db(), trials, c.protocol["biometrics"]["emg"].get<bool>());
    if (study == "pointing-short")
      for (const auto& t : trials) {
        const json measures = json::parse(t.result_json);
        for (const auto& a : measures["acquisitions"]) {
          EXPECT_TRUE(a["movement_time_s"].is_number()) << t.result_json;
          EXPECT_TRUE(a["endpoint_deg"].is_number()) << t.result_json;
        }
      }
  }
}

// Another process holds the store (an import, say) past the 10 s a trial's
// report used to be waited for: hapticd keeps the trial's samples in memory,
// the session waits while hapticd says it still holds samples to store, and
// gets the recording, complete, once the store is free.
TEST(StudyThroughHapticd, AStoppedTrialIsWaitedForWhileHapticdStillHoldsItsSamplesForABusyStore) {
  Rig rig;
  studyrun::HapticdApparatus apparatus(rig.socket());
  apparatus.start_trial({"busy-store", "P01", "c1"});
  std::this_thread::sleep_for(1s);
  auto other = store::sqlite::Connection::open(rig.db());
  other.exec("BEGIN IMMEDIATE");
  auto stopping = std::async(std::launch::async, [&] { return apparatus.stop_trial(); });
  const bool waited = stopping.wait_for(13s) == std::future_status::timeout;
  other.exec("COMMIT");
  studyrun::TrialRecording rec;
  std::string error;
  try {
    rec = stopping.get();
  } catch (const std::exception& e) {
    error = e.what();
  }
  EXPECT_TRUE(waited) << "stop_trial returned while the store was held: " << error;
  ASSERT_EQ(error, "");
  EXPECT_TRUE(rec.complete) << rec.end_reason;
  ASSERT_TRUE(rec.capture_id);
  store::Store s = store::Store::open(rig.db(), {.read_only = true});
  EXPECT_EQ(s.capture_info(*rec.capture_id)->status, "complete");
  EXPECT_GT(s.load_samples(*rec.capture_id).t.size(), 4000u);  // about a second at 5 kHz
}

// A busy emulated machine has left hapticd's telemetry silent for more than
// 5 s (SIGSTOP stands in for it here): the session waits on. A killed
// hapticd is told apart by its control socket closing, at once.
TEST(StudyThroughHapticd, TelemetryHeldUpForSecondsIsWaitedForButAKilledHapticdEndsTheReadingAtOnce) {
  Rig rig;
  studyrun::HapticdApparatus apparatus(rig.socket());
  apparatus.next();
  ::kill(rig.hapticd_pid(), SIGSTOP);
  const auto stopped = std::chrono::steady_clock::now();
  auto reading = std::async(std::launch::async, [&] {
    for (;;) {  // what was in the ring before the stop, then the first after it
      const studyrun::KnobReading r = apparatus.next();
      if (std::chrono::steady_clock::now() - stopped > 6s) return r;
    }
  });
  std::this_thread::sleep_for(7s);
  ::kill(rig.hapticd_pid(), SIGCONT);
  ASSERT_EQ(reading.wait_for(10s), std::future_status::ready) << rig.log();
  EXPECT_NO_THROW(reading.get());

  rig.stop_hapticd(SIGKILL);
  const auto killed = std::chrono::steady_clock::now();
  std::string error;
  try {
    for (;;) apparatus.next();  // the ring's last records, then the loss
  } catch (const studyrun::ApparatusError& e) {
    error = e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - killed, 2s);
  EXPECT_NE(error.find("hapticd lost"), std::string::npos) << error;
}

TEST(StudyThroughHapticd, KilledMidSessionWithHapticdItResumesAtTheNextTrialAndLosesNothingCommitted) {
  Rig rig;
  json protocol = shortened_pointing_json();
  protocol["study"] = "pointing-cut";
  const std::string file = rig.write_protocol(protocol);
  const pid_t run = spawn_knoblab(rig.simulate(file));
  ASSERT_GT(run, 0);
  ASSERT_TRUE(eventually([&] { return trials_of(rig.db(), "pointing-cut").size() >= 2; }, 60s)) << rig.log();
  // A power cut: nothing is told, everything stops at once.
  ::kill(run, SIGKILL);
  rig.stop_hapticd(SIGKILL);
  wait_exit(run, 5s);
  const auto before = trials_of(rig.db(), "pointing-cut");
  ASSERT_GE(before.size(), 2u);
  ASSERT_LT(before.size(), 4u) << "the cut came before the end";

  rig.start_hapticd();
  const RunResult r = run_knoblab(rig.simulate(file));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err << rig.log();
  EXPECT_NE(r.out.find("resumed at trial " + std::to_string(before.size() + 1)), std::string::npos) << r.out;
  const auto after = trials_of(rig.db(), "pointing-cut");
  ASSERT_EQ(after.size(), 4u);
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(after[i].trial_index, before[i].trial_index);
    EXPECT_EQ(after[i].result_json, before[i].result_json);
    EXPECT_EQ(after[i].ratings_json, before[i].ratings_json);
    EXPECT_EQ(after[i].biometrics_json, before[i].biometrics_json);
    EXPECT_EQ(after[i].capture_id, before[i].capture_id);
  }
  expect_recorded(rig.db(), after, true);
}

// Without a guided hand on hapticd's sim backend the simulated participant
// has nothing to steer: the command once waited 60 s and left an open
// session and a stray capture. It refuses before it stores anything.
TEST(StudyThroughHapticd, AHapticdWithoutAGuidedHandIsRefusedAtOnceAndNothingIsStored) {
  ScratchDir dir;
  const std::string socket = (dir / "h.sock").string(), db = (dir / "lab.sqlite").string();
  const pid_t hapticd = spawn({KNOBLAB_HAPTICD_PATH, "--backend", "sim", "--knob", "moderate-detents", "--rate", "1000",
                               "--socket", socket, "--db", db, "--max-overruns", "1000000"},
                              (dir / "hapticd.out").string(), (dir / "hapticd.err").string());
  ASSERT_GT(hapticd, 0);
  ASSERT_TRUE(eventually([&] { return run_knoblab({"ctl", "--socket", socket, "get_state"}).exit_code == 0; }))
      << read_file(dir / "hapticd.err");
  const RunResult r = run_knoblab({"study", "simulate", std::string(KNOBLAB_STUDY_EXAMPLES_DIR) + "/textures.json",
                                   "--participants", "1", "--db", db, "--socket", socket});
  ::kill(hapticd, SIGTERM);
  wait_exit(hapticd, 10s);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("has no guided hand for a simulated participant"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\"hand\": {\"channel\": \"/knoblab-sim-hand\"}"), std::string::npos) << r.err;
  auto store = store::Store::open(db);
  EXPECT_TRUE(store.study_sessions("study1-textures").empty());
  EXPECT_TRUE(store.list_captures().empty());
}

}  // namespace
}  // namespace knoblab::test
