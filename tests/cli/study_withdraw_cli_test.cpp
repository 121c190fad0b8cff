// knoblab study withdraw on three simulated participants (in simulated time):
// without --yes it only says what would go and fails, the store untouched;
// with --yes the participant is gone from `study sessions` and `study export`
// with their trials' captures, and the others remain.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "knoblab/store/store.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

const std::string kStudy = "study1-textures";

// Three participants' first two trials of the textures study, with SIM02's
// trials given captures of 600 and 900 samples: --in-process records none,
// and the withdrawal must take a participant's captures too.
std::vector<std::int64_t> simulate_three(const std::string& db) {
  const RunResult r = run_knoblab({"study", "simulate", std::string(KNOBLAB_STUDY_EXAMPLES_DIR) + "/textures.json",
                                   "--participants", "3", "--max-trials", "2", "--in-process", "--db", db});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  auto store = store::Store::open(db);
  std::int64_t session = 0;
  for (const auto& s : store.study_sessions(kStudy))
    if (s.participant == "SIM02") session = s.session_id;
  std::vector<std::int64_t> captures;
  for (const int samples : {600, 900}) {
    store::NewCapture info;
    info.source = "hapticd";
    info.rate_hz = 1000;
    auto w = store.begin_capture(info);
    for (int i = 0; i < samples; ++i) w.append({i * 1e-3, 0.01 * i, 0.5, 0.0, 0.001, 0.0});
    w.finish();
    captures.push_back(w.capture_id());
    store.connection()
        .prepare("UPDATE study_trials SET capture_id = ?1 WHERE session_id = ?2 AND trial_index = ?3")
        .bind_int(1, w.capture_id())
        .bind_int(2, session)
        .bind_int(3, static_cast<std::int64_t>(captures.size()))
        .run();
  }
  return captures;
}

std::size_t lines_starting(const std::string& text, const std::string& prefix) {
  std::size_t n = 0;
  for (std::size_t at = 0; at < text.size();) {
    if (text.compare(at, prefix.size(), prefix) == 0) ++n;
    const auto end = text.find('\n', at);
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return n;
}

TEST(StudyWithdrawCli, WithoutYesItSaysWhatWouldBeDeletedFailsAndLeavesTheStoreUntouched) {
  ScratchDir dir;
  const std::string db = (dir / "lab.sqlite").string();
  simulate_three(db);
  const std::string bytes = read_file(db);
  const RunResult sessions = run_knoblab({"study", "sessions", kStudy, "--db", db});

  const RunResult r = run_knoblab({"study", "withdraw", kStudy, "SIM02", "--db", db});

  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.out, "SIM02 of " + kStudy + ": would delete 1 session, 2 trials, 0 notes, 2 captures (1 500 samples)\n");
  EXPECT_NE(r.err.find("add --yes"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(db), bytes) << "the store file changed";
  EXPECT_EQ(run_knoblab({"study", "sessions", kStudy, "--db", db}).out, sessions.out);
}

TEST(StudyWithdrawCli, WithYesTheParticipantIsGoneFromSessionsAndExportWhileTheOthersRemain) {
  ScratchDir dir;
  const std::string db = (dir / "lab.sqlite").string();
  const std::vector<std::int64_t> captures = simulate_three(db);

  RunResult r = run_knoblab({"study", "withdraw", kStudy, "SIM02", "--db", db, "--yes"});

  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out, "SIM02 withdrawn from " + kStudy + ": 1 session, 2 trials, 0 notes, 2 captures (1 500 samples) deleted\n");
  r = run_knoblab({"study", "sessions", kStudy, "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("SIM02"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("SIM01"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("SIM03"), std::string::npos) << r.out;
  const std::string csv = (dir / "trials.csv").string();
  r = run_knoblab({"study", "export", kStudy, "--db", db, "--out", csv});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string exported = read_file(csv);
  EXPECT_EQ(lines_starting(exported, "SIM02,"), 0u) << exported;
  EXPECT_EQ(lines_starting(exported, "SIM01,"), 2u) << exported;
  EXPECT_EQ(lines_starting(exported, "SIM03,"), 2u) << exported;
  {
    auto store = store::Store::open(db, {.read_only = true});
    for (const auto id : captures) EXPECT_FALSE(store.capture_info(id)) << "capture " << id;
  }

  r = run_knoblab({"study", "withdraw", kStudy, "SIM02", "--db", db, "--yes"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("participant 'SIM02' has no session of study '" + kStudy + "'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("SIM01, SIM03"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace knoblab::test
