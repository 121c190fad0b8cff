// knoblab discrepancy --report DIR end to end: on a simulated capture with a
// concealed periodic torque, the text output's fit % and whiteness p, the
// report files and the JSON's new figures; a report directory that cannot
// be made.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "process.hpp"

namespace knoblab::test {
namespace {

namespace fs = std::filesystem;

TEST(DiscrepancyReportCli, WritesTheReportAndPrintsTheFigures) {
  ScratchDir dir;
  const auto csv = dir / "cogged.csv";
  const RunResult sim = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "8",
                                     "--effects", "periodic_torque:amplitude_Nm=0.001,period_rad=0.36316811075498007,phase_rad=0.3",
                                     "--out", csv.string()});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto report = dir / "report";
  const auto json = dir / "r.json";
  const RunResult r = run_knoblab({"discrepancy", "--input", csv.string(), "--report",
                                   report.string(), "--json", json.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* line : {"base model: RMS", "final model: RMS"}) {
    const std::size_t at = r.out.find(line);
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string rest = r.out.substr(at, r.out.find('\n', at) - at);
    EXPECT_NE(rest.find(" fit "), std::string::npos) << rest;
    EXPECT_NE(rest.find("whiteness p "), std::string::npos) << rest;
  }
  EXPECT_NE(r.out.find("report: 21 files in " + report.string()), std::string::npos) << r.out;
  for (const char* stem : {"residual_position", "residual_velocity", "residual_time", "whiteness", "summary"})
    for (const char* ext : {".pdf", ".svg", ".png", ".csv"})
      EXPECT_TRUE(fs::is_regular_file(report / (std::string(stem) + ext))) << stem << ext;
  const std::string md = read_file(report / "summary.md");
  EXPECT_NE(md.find("+ periodic_torque (final)"), std::string::npos) << md;
  const std::string j = read_file(json);
  for (const char* key : {"\"fit_percent\"", "\"whiteness_p\"", "\"independence_p\"", "\"heldout_rmse_Nm\""})
    EXPECT_NE(j.find(key), std::string::npos) << key;
}

TEST(DiscrepancyReportCli, MinGainAboveTheFindingsGainLeavesThemTentative) {
  ScratchDir dir;
  const auto csv = dir / "cogged.csv";
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "8", "--effects",
                         "periodic_torque:amplitude_Nm=0.001,period_rad=0.36316811075498007,phase_rad=0.3", "--out", csv.string()}).exit_code, 0);
  const auto json = dir / "r.json";
  const RunResult r = run_knoblab({"discrepancy", "--input", csv.string(), "--min-gain", "99", "--json",
                                   json.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("under the 99 % a finding must earn"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  (periodic_torque, "), std::string::npos) << r.out;
  const std::string j = read_file(json);
  EXPECT_NE(j.find("\"findings\": []"), std::string::npos) << j;
  EXPECT_NE(j.find("\"tentative_heldout_rmse_Nm\""), std::string::npos) << j;
  const RunResult bad = run_knoblab({"discrepancy", "--input", csv.string(), "--min-gain", "120"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--min-gain"), std::string::npos) << bad.err;
}

TEST(DiscrepancyReportCli, UnmakeableReportDirectoryIsAnErrorNamingIt) {
  ScratchDir dir;
  const auto csv = dir / "clean.csv";
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "4", "--out",
                         csv.string()}).exit_code, 0);
  write_file(dir / "plain", "not a directory");
  const auto target = dir / "plain" / "report";
  const RunResult r = run_knoblab({"discrepancy", "--input", csv.string(), "--report", target.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.err.find(target.string()), std::string::npos) << r.err;
}

}  // namespace
}  // namespace knoblab::test
