// knoblab discrepancy and knoblab fit on a linear actuator's capture: a
// simulated knob's CSV read as metres and newtons, by a '# axis: linear'
// line or by --linear. The text is in mm, N, N/m and mm per cycle, the JSON
// SI with "axis": "linear"; the same file without either stays rotary.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "process.hpp"

namespace knoblab::test {
namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// What a linear axis's text must never say.
void expect_linear_words(const std::string& text) {
  for (const char* rotary : {"revolution", "/rev", "°", "mN·m", "rad/s"})
    EXPECT_FALSE(contains(text, rotary)) << "'" << rotary << "' in:\n" << text;
}

// A spring and cogging concealed in the moderate-detents knob, simulated
// once for every test here: rail.csv as simulated, rail-linear.csv the same
// with '# axis: linear' first.
class LinearAxisCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir;
    const RunResult sim = run_knoblab(
        {"simulate", "--knob", "moderate-detents", "--seconds", "8", "--effects",
         "spring:stiffness_Nm_per_rad=0.01;periodic_torque:amplitude_Nm=0.002,period_rad=0.36316811075498007,phase_rad=0.3",
         "--out", rotary_csv().string()});
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    write_file(linear_csv(), "# axis: linear\n" + read_file(rotary_csv()));
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::filesystem::path rotary_csv() { return *dir_ / "rail.csv"; }
  static std::filesystem::path linear_csv() { return *dir_ / "rail-linear.csv"; }
  static std::filesystem::path path(const std::string& name) { return *dir_ / name; }

  static ScratchDir* dir_;
};
ScratchDir* LinearAxisCli::dir_ = nullptr;

// The findings' text of a discrepancy JSON, and its effects in order.
std::string findings_text(const nlohmann::json& j) {
  std::string text;
  for (const auto& f : j["findings"])
    text += f["effect"].get<std::string>() + ": " + f["where"].get<std::string>() + " — " +
            f["explanation"].get<std::string>() + "\n";
  return text;
}

TEST_F(LinearAxisCli, AnAxisLineMakesDiscrepancySpeakInMillimetresNewtonsAndMillimetresPerCycle) {
  const RunResult r =
      run_knoblab({"discrepancy", linear_csv().string(), "--json", path("linear.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_linear_words(r.out);
  EXPECT_TRUE(contains(r.out, "- spring (")) << r.out;
  EXPECT_TRUE(contains(r.out, " N/m")) << r.out;
  EXPECT_TRUE(contains(r.out, "- periodic_torque (")) << r.out;
  EXPECT_TRUE(contains(r.out, " mm per cycle")) << r.out;
  EXPECT_TRUE(contains(r.out, "held-out RMS ")) << r.out;
  const auto j = nlohmann::json::parse(read_file(path("linear.json")));
  EXPECT_EQ(j["axis"], "linear");
  expect_linear_words(findings_text(j));
  // Gravity is no candidate on a linear axis.
  for (const auto& c : j["candidates"]) EXPECT_NE(c["effect"], "gravity");
}

TEST_F(LinearAxisCli, TheLinearFlagOnAFileWithoutTheLineSaysTheSame) {
  const RunResult r =
      run_knoblab({"discrepancy", rotary_csv().string(), "--linear", "--json", path("flag.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_linear_words(r.out);
  const auto flag = nlohmann::json::parse(read_file(path("flag.json")));
  EXPECT_EQ(flag["axis"], "linear");
  const RunResult line = run_knoblab({"discrepancy", linear_csv().string(), "--json", path("line.json").string()});
  ASSERT_EQ(line.exit_code, 0) << line.err;
  EXPECT_EQ(findings_text(flag), findings_text(nlohmann::json::parse(read_file(path("line.json")))));
}

TEST_F(LinearAxisCli, ARotaryCaptureKeepsMilliNewtonMetresAndCyclesPerRevolution) {
  const RunResult r = run_knoblab({"discrepancy", rotary_csv().string(), "--json", path("rotary.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "mN·m")) << r.out;
  EXPECT_TRUE(contains(r.out, "cycles per revolution")) << r.out;
  EXPECT_FALSE(nlohmann::json::parse(read_file(path("rotary.json"))).contains("axis"));
}

TEST_F(LinearAxisCli, FitTellsForcesInNewtonsAndTheDetentsAsAPeriodInMillimetres) {
  const RunResult r = run_knoblab({"fit", linear_csv().string(), "--json", path("fit.json").string(), "--report",
                                   path("fit-report").string(), "--format", "svg"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_linear_words(r.out);
  for (const char* unit : {" kg\n", " N·s/m\n", " N\n", "detents: ", " mm per cycle"})
    EXPECT_TRUE(contains(r.out, unit)) << unit << " in:\n" << r.out;
  const auto j = nlohmann::json::parse(read_file(path("fit.json")));
  EXPECT_EQ(j["axis"], "linear");
  // The report's data: positions in mm, forces in N.
  const std::string csv = read_file(path("fit-report") / "torque_position.csv");
  EXPECT_TRUE(csv.starts_with("panel,series,position_mm,force_N,force_lower_N\n")) << csv.substr(0, 80);
}

TEST_F(LinearAxisCli, AnImportedLinearCaptureStaysLinearInTheStore) {
  const auto db = path("lab.sqlite");
  ASSERT_EQ(run_knoblab({"import", linear_csv().string(), "--db", db.string()}).exit_code, 0);
  const RunResult r = run_knoblab({"fit", "--capture", "1", "--db", db.string(), "--json", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["axis"], "linear") << r.out;
}

TEST_F(LinearAxisCli, AnUnknownAxisIsRefusedNamingTheFileAndTheValue) {
  const auto bad = path("bad-axis.csv");
  write_file(bad, "# axis: angular\n" + read_file(rotary_csv()));
  const RunResult r = run_knoblab({"fit", bad.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, bad.string() + ": metadata 'axis' is 'angular': expected rotary or linear")) << r.err;
}

TEST_F(LinearAxisCli, TheLinearFlagIsRefusedForACaptureThatSaysItIsRotary) {
  const auto rotary = path("says-rotary.csv");
  write_file(rotary, "# axis: rotary\n" + read_file(rotary_csv()));
  const RunResult r = run_knoblab({"fit", rotary.string(), "--linear"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(contains(r.err, "says 'axis: rotary', not linear")) << r.err;
}

TEST_F(LinearAxisCli, GravityAsACandidateOnALinearAxisIsAUsageError) {
  const RunResult r = run_knoblab({"discrepancy", linear_csv().string(), "--effects", "offset,gravity"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "a linear axis has no once-per-revolution torque")) << r.err;
}

}  // namespace
}  // namespace knoblab::test
