// Twelve simulated participants do the whole rotary pointing study (4 blocks
// of 28) on hapticd's core in simulated time; `knoblab study export` writes
// the tidy CSV, `knoblab study report` the analysis and figures, and an
// independent base-R analysis of the same CSV (tests/study/pointing_reference.R)
// must give every figure of the report's JSON to 1e-6.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "process.hpp"
#include "r_reference.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;

TEST(StudyReport, TwelveSimulatedParticipantsOfThePointingStudyAgreeWithRToOnePartInAMillion) {
  ScratchDir dir;
  const std::string db = (dir / "lab.sqlite").string();
  const std::string protocol = std::string(KNOBLAB_STUDY_EXAMPLES_DIR) + "/pointing.json";
  RunResult r = run_knoblab({"study", "simulate", protocol, "--participants", "12", "--db", db, "--in-process"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("SIM12: session"), std::string::npos) << r.out;

  const std::string study = json::parse(std::ifstream(protocol))["study"];
  r = run_knoblab({"study", "sessions", study, "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t finished = 0;
  for (std::size_t at = 0; (at = r.out.find("112/112   finished (simulated)", at)) != std::string::npos; ++at) ++finished;
  EXPECT_EQ(finished, 12u) << r.out;

  const std::string csv = (dir / "trials.csv").string();
  r = run_knoblab({"study", "export", study, "--db", db, "--out", csv});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(csv);
  const std::vector<study::PointingRow> rows = study::read_pointing_csv(in);
  // Every acquisition of every trial, but those of a trial that timed out
  // (a target the simulated hand could not place the knob on).
  EXPECT_GE(rows.size(), 12u * 112u * 3u * 99 / 100);

  const std::string report_json = (dir / "report.json").string();
  r = run_knoblab({"study", "report", study, "--db", db, "--out", (dir / "report").string(), "--json", report_json,
                   "--format", "png"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // The terminal shows the Fitts table and the ANOVA.
  EXPECT_NE(r.out.find("We"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Greenhouse"), std::string::npos) << r.out;
  const json ours = json::parse(std::ifstream(report_json));
  ASSERT_EQ(ours["renderings"].size(), 7u);
  EXPECT_EQ(ours["participants"].size(), 12u);

  const json ref = study::test::r_pointing_reference(
      rows, {"not-rendered", "low-friction", "high-friction", "low-inertia", "high-inertia", "few-detents",
             "many-detents"});
  const std::size_t compared = study::test::expect_same(ours, ref, "report");
  EXPECT_GT(compared, 200u);
  for (const char* figure : {"movement_time.png", "fitts.png", "rating.png"})
    EXPECT_GT(std::filesystem::file_size(dir / "report" / figure), 10000u) << figure;
  if (const char* keep = std::getenv("KNOBLAB_KEEP_STUDY_REPORT"))  // to look at the figures
    std::filesystem::copy(dir / "report", keep, std::filesystem::copy_options::recursive |
                                                    std::filesystem::copy_options::overwrite_existing);
}

}  // namespace
}  // namespace knoblab::test
