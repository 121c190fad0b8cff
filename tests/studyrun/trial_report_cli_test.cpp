// The other kinds' report from the command line: three simulated novices
// match the five thesis knobs (in simulated time); `knoblab study report`
// compares their satisfaction across the knobs and their settings with each
// knob's own values, and writes the figures.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "process.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;

TEST(StudyReport, ThreeSimulatedNovicesMatchingTheFiveKnobsAreComparedWithEachKnobsOwnValues) {
  ScratchDir dir;
  const std::string db = (dir / "lab.sqlite").string();
  const std::string protocol = std::string(KNOBLAB_STUDY_EXAMPLES_DIR) + "/matching-novice.json";
  RunResult r = run_knoblab({"study", "simulate", protocol, "--participants", "3", "--db", db, "--in-process"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::string study = json::parse(std::ifstream(protocol))["study"];

  const std::string report_json = (dir / "report.json").string();
  r = run_knoblab({"study", "report", study, "--db", db, "--out", (dir / "report").string(), "--json", report_json,
                   "--format", "png"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Friedman"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Matched against the reference knobs"), std::string::npos) << r.out;
  const json ours = json::parse(std::ifstream(report_json));
  EXPECT_EQ(ours["factor"], "knob");
  ASSERT_EQ(ours["levels"].size(), 5u);
  EXPECT_EQ(ours["levels"][0]["level"], "A");
  EXPECT_EQ(ours["levels"][0]["trials"], 9u);  // three repetitions of three participants
  EXPECT_EQ(ours["participants"].size(), 3u);
  ASSERT_EQ(ours["scales"].size(), 1u);
  EXPECT_EQ(ours["scales"][0]["scale"], "satisfaction");
  // Every knob's inertia and damping is matched (the first stage has only
  // those two sliders); detents only on C, D, E. The simulated novices feel
  // magnitudes off by a ratio (about 25 %), so their mean lands near the knob's.
  std::size_t inertia = 0, detents = 0;
  for (const json& m : ours["matches"]) {
    if (m["parameter"] == "M_acc") {
      ++inertia;
      EXPECT_GT(m["ratio"].get<double>(), 0.5) << m.dump();
      EXPECT_LT(m["ratio"].get<double>(), 2.0) << m.dump();
    }
    if (m["parameter"] == "detents_per_rev") ++detents;
  }
  EXPECT_EQ(inertia, 5u);
  EXPECT_EQ(detents, 3u);
  for (const char* figure : {"rating_satisfaction.png", "match_M_acc.png", "match_detents_per_rev.png"})
    EXPECT_GT(std::filesystem::file_size(dir / "report" / figure), 10000u) << figure;

  r = run_knoblab({"study", "report", study, "--db", db, "--out", (dir / "report").string(), "--factor", "colour"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("the protocol has no factor 'colour' (it has knob)"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace knoblab::test
