// One command-line grammar: the same input forms, metavars, examples and
// machine-readable listings in every command.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "process.hpp"

namespace knoblab::test {
namespace {

// The command names `knoblab --help` lists, with their one-line summaries.
std::vector<std::pair<std::string, std::string>> overview() {
  const RunResult r = run_knoblab({"--help"});
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(r.out);
  std::string line;
  bool in_list = false;
  while (std::getline(in, line)) {
    if (line == "commands:") in_list = true;
    else if (line.empty()) in_list = false;
    else if (in_list) {
      std::istringstream words(line);
      std::string name;
      words >> name;
      std::string rest;
      std::getline(words, rest);
      out.emplace_back(name, rest.substr(rest.find_first_not_of(' ')));
    }
  }
  return out;
}

TEST(Grammar, TheOverviewGivesEachCommandAWholeSentence) {
  const auto commands = overview();
  ASSERT_GE(commands.size(), 10u);
  for (const auto& [name, summary] : commands) EXPECT_EQ(summary.back(), '.') << name << ": " << summary;
}

TEST(Grammar, EveryHelpNamesItsValuesAndEndsWithAnExample) {
  for (const auto& [name, summary] : overview()) {
    const RunResult r = run_knoblab({name, "--help"});
    EXPECT_EQ(r.exit_code, 0) << name;
    EXPECT_EQ(r.out.find(" VALUE"), std::string::npos) << name << " has an option without a metavar:\n" << r.out;
    const auto ex = r.out.find("\nexample");
    ASSERT_NE(ex, std::string::npos) << name << " has no example:\n" << r.out;
    EXPECT_NE(r.out.find("knoblab " + name, ex), std::string::npos) << name;
  }
}

TEST(Grammar, VersionIsTheSameForTheToolAndEachCommand) {
  const RunResult top = run_knoblab({"--version"});
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_EQ(top.out.rfind("knoblab ", 0), 0u) << top.out;
  EXPECT_EQ(run_knoblab({"fit", "--version"}).out, top.out);
}

class WithACapture : public ::testing::Test {
 protected:
  void SetUp() override {
    const RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "2", "--out",
                                     csv_.string(), "--db", db_.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  ScratchDir dir_;
  std::filesystem::path csv_ = dir_ / "knob.csv", db_ = dir_ / "lab.sqlite";
};

TEST_F(WithACapture, TheInputFileIsAPositionalOrInputInEveryCommandThatReadsOne) {
  for (const std::string cmd : {"inspect", "fit"}) {
    const RunResult a = run_knoblab({cmd, csv_.string()});
    const RunResult b = run_knoblab({cmd, "--input", csv_.string()});
    EXPECT_EQ(a.exit_code, 0) << cmd << a.err;
    // The same result; only the fit's "…, 0.016 s" timing may differ.
    const auto untimed = [](std::string s) {
      const auto t = s.find(" iterations, ");
      if (t != std::string::npos) s.erase(t, s.find('\n', t) - t);
      return s;
    };
    EXPECT_EQ(untimed(a.out), untimed(b.out)) << cmd;
  }
  const RunResult both = run_knoblab({"inspect", csv_.string(), "--input", csv_.string()});
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("not both"), std::string::npos) << both.err;
}

TEST(Grammar, AMisspeltOptionGetsAGuessAndACaptureIdWithoutItsOptionAHint) {
  RunResult r = run_knoblab({"fit", "--inptu", "x.csv"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("did you mean --input?"), std::string::npos) << r.err;
  r = run_knoblab({"discrepancy", "--db", "lab.sqlite", "7"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--capture 7"), std::string::npos) << r.err;
  r = run_knoblab({"inspect", "--capture", "seven", "--db", "lab.sqlite"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--capture must be an id"), std::string::npos) << r.err;
}

TEST_F(WithACapture, ListAndInspectPrintJsonAndCsvInSiUnits) {
  RunResult r = run_knoblab({"list", "--db", db_.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto list = nlohmann::json::parse(r.out);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["knob"], "moderate-detents");
  EXPECT_EQ(list[0]["status"], "complete");
  EXPECT_EQ(list[0]["rate_hz"].get<double>(), 5000.0);

  r = run_knoblab({"list", "--db", db_.string(), "--csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("id,knob,mode,status,samples,rate_hz,started_at,end_reason\n1,moderate-detents,lab,complete,",
                        0), 0u)
      << r.out;

  r = run_knoblab({"inspect", csv_.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_NEAR(summary["detent_cycles_per_rev"].get<double>(), 12.0, 0.5);
  EXPECT_LT(summary["theta_max_rad"].get<double>(), 7.0);  // radians, not degrees

  r = run_knoblab({"inspect", csv_.string(), "--csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream rows(r.out);
  std::string header, row, extra;
  std::getline(rows, header);
  std::getline(rows, row);
  EXPECT_FALSE(std::getline(rows, extra));
  EXPECT_EQ(header.rfind("samples,duration_s,", 0), 0u) << header;
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(row.begin(), row.end(), ','));

  r = run_knoblab({"list", "--db", db_.string(), "--csv", "--json"});
  EXPECT_EQ(r.exit_code, 2);
}

TEST_F(WithACapture, FitsPrintJsonAndCsvWithTheirProvenance) {
  ASSERT_EQ(run_knoblab({"fit", "--capture", "1", "--db", db_.string()}).exit_code, 0);
  RunResult r = run_knoblab({"fits", "--db", db_.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto fits = nlohmann::json::parse(r.out);
  ASSERT_EQ(fits.size(), 1u) << r.out;
  EXPECT_EQ(fits[0]["capture_id"], 1);
  EXPECT_EQ(fits[0]["model"], "thesis6");
  EXPECT_LT(fits[0]["rmse_Nm"].get<double>(), 0.01);  // N·m, not mN·m
  EXPECT_EQ(fits[0]["input_sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(fits[0]["tool_version"], run_knoblab({"--version"}).out.substr(8, run_knoblab({"--version"}).out.size() - 9));
  r = run_knoblab({"fits", "--db", db_.string(), "--csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("id,capture_id,model,created_at,rmse_Nm,fit_percent,detents_per_rev,files,tool_version,"
                        "input_sha256\n1,1,thesis6,",
                        0),
            0u)
      << r.out;
}

TEST(Grammar, CsvListingsQuoteTextThatHoldsCommasAndQuotes) {
  ScratchDir dir;
  const auto csv = dir / "k.csv";
  write_file(csv, "t,theta,torque\n0,0,0\n0.001,0.001,0.001\n0.002,0.002,0.002\n");
  const RunResult imp = run_knoblab({"import", csv.string(), "--db", (dir / "s.sqlite").string(), "--knob",
                                     "fan, \"Mazda\" 626"});
  ASSERT_EQ(imp.exit_code, 0) << imp.err;
  const RunResult r = run_knoblab({"list", "--db", (dir / "s.sqlite").string(), "--csv"});
  EXPECT_NE(r.out.find(",\"fan, \"\"Mazda\"\" 626\",lab,"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace knoblab::test
