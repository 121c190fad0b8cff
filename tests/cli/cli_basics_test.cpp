// The command line itself: help, usage errors, exit codes.
#include <gtest/gtest.h>

#include "process.hpp"

namespace knoblab::test {
namespace {

TEST(Cli, OverviewListsEveryCommand) {
  const RunResult r = run_knoblab({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* c : {"simulate", "import", "export", "list", "inspect", "demo"})
    EXPECT_NE(r.out.find(c), std::string::npos) << c;
}

TEST(Cli, EachCommandHasHelp) {
  for (const char* c : {"simulate", "import", "export", "list", "inspect", "demo"}) {
    const RunResult r = run_knoblab({c, "--help"});
    EXPECT_EQ(r.exit_code, 0) << c;
    EXPECT_NE(r.out.find(std::string("usage: knoblab ") + c), std::string::npos) << r.out;
  }
}

TEST(Cli, UsageErrorsExitTwoWithAClearMessage) {
  EXPECT_EQ(run_knoblab({}).exit_code, 2);
  RunResult r = run_knoblab({"frobnicate"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown command 'frobnicate'"), std::string::npos) << r.err;
  r = run_knoblab({"simulate", "--knob", "moderate-detents", "--bogus"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown option --bogus"), std::string::npos) << r.err;
  r = run_knoblab({"simulate", "--knob", "no-such-knob"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown knob preset 'no-such-knob'"), std::string::npos) << r.err;
  r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "abc"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--seconds: not a number"), std::string::npos) << r.err;
  r = run_knoblab({"simulate", "--knob", "moderate-detents", "--rate", "50000"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--rate must be in [1, 20000]"), std::string::npos) << r.err;
  r = run_knoblab({"export", "x", "--db", "/tmp/none.sqlite", "--out", "/tmp/none.csv"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("CAPTURE must be an id"), std::string::npos) << r.err;
}

TEST(Cli, SimulateListsPresets) {
  const RunResult r = run_knoblab({"simulate", "--list"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* k : {"high-friction", "high-inertia", "subtle-detents", "moderate-detents",
                        "non-sine-detents", "study2-many-detents", "study3-high-inertia"})
    EXPECT_NE(r.out.find(k), std::string::npos) << k;
}

}  // namespace
}  // namespace knoblab::test
