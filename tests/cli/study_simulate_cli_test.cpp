// knoblab study simulate's progress: one line redrawn on a terminal, nothing
// in a pipe or a log (where carriage returns ran the lines together), and a
// JSON line per committed trial for knoblab-ui.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "process.hpp"

namespace knoblab::test {
namespace {

RunResult simulate_two_trials(const std::string& db) {
  return run_knoblab({"study", "simulate", std::string(KNOBLAB_STUDY_EXAMPLES_DIR) + "/textures.json", "--participants",
                      "1", "--max-trials", "2", "--in-process", "--db", db});
}

TEST(StudySimulateCli, InAPipeStderrHoldsNoProgressAndStdoutTheSessionsOneLine) {
  ScratchDir dir;
  const RunResult r = simulate_two_trials((dir / "lab.sqlite").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("committed"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "SIM01: session 1, 2 trials run, not finished\n");
}

TEST(StudySimulateCli, ForTheUiEachCommittedTrialIsAJsonProgressLine) {
  ScratchDir dir;
  ::setenv("KNOBLAB_PROGRESS", "json", 1);
  const RunResult r = simulate_two_trials((dir / "lab.sqlite").string());
  ::unsetenv("KNOBLAB_PROGRESS");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find(R"({"progress":{"command":"study simulate","done":0,"stage":"SIM01: trial 1 committed","total":0}})"
                       "\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(R"("stage":"SIM01: trial 2 committed")"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace knoblab::test
