// Stored results with their provenance and report files, end to end: the
// real knoblab fits and discovers on a simulated capture in a store, then
// `knoblab fits` and `knoblab results` list them and write one out.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "knoblab/interchange/digest.hpp"
#include "knoblab/store/schema.hpp"
#include "knoblab/store/store.hpp"
#include "knoblab/version.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

// Every file in a directory, name → bytes.
std::map<std::string, std::string> files_in(const std::filesystem::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) out[e.path().filename().string()] = read_file(e.path());
  return out;
}

std::map<std::string, std::string> as_map(const std::vector<store::ResultFile>& files) {
  std::map<std::string, std::string> out;
  for (const auto& f : files) out[f.name] = std::string(f.bytes.begin(), f.bytes.end());
  return out;
}

// The lines of a text that start with `prefix`.
std::vector<std::string> lines_starting(const std::string& text, const std::string& prefix) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    if (text.compare(pos, prefix.size(), prefix) == 0) out.push_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  return out;
}

class ResultsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = (dir_ / "k.db").string();
    for (int i = 0; i < 2; ++i) {  // captures 1 and 2: two recordings of one knob
      const RunResult r =
          run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "4", "--db", db_});
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    auto store = store::Store::open(db_);
    sha_[1] = interchange::samples_sha256(store.load_samples(1));
    sha_[2] = interchange::samples_sha256(store.load_samples(2));
  }

  RunResult fit_with_report() {
    return run_knoblab({"fit", "--capture", "1", "--db", db_, "--report", (dir_ / "fit_report").string()});
  }
  RunResult discrepancy_with_report() {
    return run_knoblab({"discrepancy", "--capture", "1", "--heldout-capture", "2", "--db", db_, "--effects",
                        "offset,gravity", "--report", (dir_ / "d_report").string()});
  }

  ScratchDir dir_;
  std::string db_;
  std::map<int, std::string> sha_;  // capture → samples digest
};

TEST_F(ResultsCli, AStoredFitKeepsItsReportFilesAndItsProvenance) {
  const RunResult r = fit_with_report();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto written = files_in(dir_ / "fit_report");
  EXPECT_EQ(written.size(), 18u);  // four figures as PDF, SVG, PNG and CSV, fit.json, render_model.json
  EXPECT_NE(r.out.find("report: 18 files in "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("stored as fit 1\n"), std::string::npos) << r.out;

  auto store = store::Store::open(db_);
  const auto fit = store.fit_info(1);
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->file_count, 18);
  EXPECT_EQ(as_map(store.load_fit_files(1)), written);  // the same bytes as the report directory
  EXPECT_EQ(written.at("fit.json"), fit->result + "\n");
  ASSERT_TRUE(fit->provenance);
  EXPECT_EQ(fit->provenance->tool_version, knoblab::kVersion);
  EXPECT_EQ(fit->provenance->input_sha256, sha_[1]);
  EXPECT_EQ(nlohmann::json::parse(fit->provenance->options),
            nlohmann::json::parse(R"({"alpha":"accel","filter":true,"model":"thesis6","detents":"auto",
                                      "stick_band":true})"));

  // `knoblab fits`: nine files and the provenance in its last two columns.
  const RunResult fits = run_knoblab({"fits", "--db", db_});
  ASSERT_EQ(fits.exit_code, 0) << fits.err;
  const auto rows = lines_starting(fits.out, "     1        1  thesis6");
  ASSERT_EQ(rows.size(), 1u) << fits.out;
  std::string version = knoblab::kVersion;
  version.resize(25, ' ');
  const std::string tail = "    18  " + version + " " + sha_[1].substr(0, 12);
  EXPECT_EQ(rows[0].substr(rows[0].size() - tail.size()), tail) << rows[0];
}

TEST_F(ResultsCli, AStoredDiscrepancyResultKeepsItsReportFilesAndItsProvenance) {
  const RunResult r = discrepancy_with_report();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto written = files_in(dir_ / "d_report");
  EXPECT_EQ(written.size(), 21u);  // five figures as PDF, SVG, PNG and CSV, summary.md
  EXPECT_NE(r.out.find("stored as discrepancy 1\n"), std::string::npos) << r.out;

  auto store = store::Store::open(db_);
  const auto d = store.discrepancy_info(1);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->file_count, 21);
  EXPECT_EQ(as_map(store.load_discrepancy_files(1)), written);
  ASSERT_TRUE(d->provenance);
  EXPECT_EQ(d->provenance->tool_version, knoblab::kVersion);
  EXPECT_EQ(d->provenance->input_sha256, sha_[1]);
  const auto options = nlohmann::json::parse(d->provenance->options);
  EXPECT_EQ(options["effects"], nlohmann::json::parse(R"(["offset", "gravity"])"));
  EXPECT_EQ(options["max_findings"], 4);
  EXPECT_EQ(options["min_gain_percent"], 20.0);
  EXPECT_EQ(options["alpha"], "accel");
  EXPECT_EQ(options["filter"], true);
  EXPECT_EQ(options["heldout"], (nlohmann::json{{"capture", 2}, {"sha256", sha_[2]}}));
}

TEST_F(ResultsCli, ListsFitsAndDiscrepancyResultsTogetherAndWritesOneOutWhole) {
  ASSERT_EQ(fit_with_report().exit_code, 0);
  ASSERT_EQ(discrepancy_with_report().exit_code, 0);

  RunResult r = run_knoblab({"results", "--db", db_});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::string version = knoblab::kVersion;
  ASSERT_EQ(lines_starting(r.out, "kind ").size(), 1u) << r.out;
  const auto fit_rows = lines_starting(r.out, "fit               1        1  ");
  ASSERT_EQ(fit_rows.size(), 1u) << r.out;
  std::string column = version;  // the table's version column is 25 wide
  column.resize(25, ' ');
  EXPECT_NE(fit_rows[0].find("  " + column + "    18  rmse "), std::string::npos) << fit_rows[0];
  EXPECT_NE(fit_rows[0].find(" mN·m, 12.00 detents/rev"), std::string::npos) << fit_rows[0];
  const auto d_rows = lines_starting(r.out, "discrepancy       1        1  ");
  ASSERT_EQ(d_rows.size(), 1u) << r.out;
  EXPECT_NE(d_rows[0].find("  " + column + "    21  held-out rms "), std::string::npos) << d_rows[0];
  EXPECT_LT(r.out.find("\nfit "), r.out.find("\ndiscrepancy "));  // oldest first

  r = run_knoblab({"results", "--db", db_, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto all = nlohmann::json::parse(r.out);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0]["kind"], "fit");
  EXPECT_EQ(all[0]["files"], 18);
  EXPECT_EQ(all[0]["input_sha256"], sha_[1]);
  EXPECT_EQ(all[0]["options"]["model"], "thesis6");
  EXPECT_GT(all[0]["key"]["rmse_Nm"].get<double>(), 0.0);
  EXPECT_EQ(all[1]["kind"], "discrepancy");
  EXPECT_EQ(all[1]["heldout_capture_id"], 2);
  EXPECT_EQ(all[1]["files"], 21);
  EXPECT_EQ(all[1]["tool_version"], version);

  // One of them, whole.
  const auto out = dir_ / "out" / "d1";
  r = run_knoblab({"results", "1", "--kind", "discrepancy", "--db", db_, "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto store = store::Store::open(db_);
  const auto d = store.discrepancy_info(1);
  EXPECT_EQ(read_file(out / "result.json"), d->result + "\n");
  EXPECT_EQ(files_in(out / "report"), as_map(store.load_discrepancy_files(1)));
  const auto provenance = nlohmann::json::parse(read_file(out / "provenance.json"));
  EXPECT_EQ(provenance["kind"], "discrepancy");
  EXPECT_EQ(provenance["input_sha256"], sha_[1]);
  EXPECT_EQ(provenance["options"]["heldout"]["sha256"], sha_[2]);
  EXPECT_EQ(provenance["report"].size(), 21u);
  std::size_t total = 0;
  for (const auto& f : store.load_discrepancy_files(1)) total += f.bytes.size();
  EXPECT_EQ(r.out, "discrepancy 1: result.json, provenance.json and 21 report files (" + std::to_string(total) +
                       " bytes) written to " + out.string() + "\n");

  // Its description on the screen.
  r = run_knoblab({"results", "1", "--kind", "fit", "--db", db_});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("fit 1 of capture 1, stored "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  made by:   knoblab " + version + "\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  input:     SHA-256 " + sha_[1] + " of capture 1's samples\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  files:     18:\n    ci_torque.csv ("), std::string::npos) << r.out;
}

TEST_F(ResultsCli, RefusesWhatItCannotDoAndWritesNothing) {
  ASSERT_EQ(fit_with_report().exit_code, 0);
  const auto out = dir_ / "out";
  struct Case {
    std::vector<std::string> args;
    int exit_code;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"results", "1", "--db", db_, "--out", out.string()}, 2, "give --kind fit or --kind discrepancy"},
      {{"results", "1", "--kind", "fits", "--db", db_}, 2, "--kind must be fit or discrepancy, got 'fits'"},
      {{"results", "x", "--kind", "fit", "--db", db_}, 2, "ID must be a result id (a positive integer), got 'x'"},
      {{"results", "--kind", "fit", "--db", db_}, 2, "--kind and --out go with a result ID"},
      {{"results", "1", "--kind", "fit", "--db", db_, "--out", ""}, 2, "--out needs a directory"},
      {{"results", "1", "--kind", "discrepancy", "--db", db_, "--out", out.string()}, 1,
       "no discrepancy 1 in the store"},
      {{"results", "--db", (dir_ / "missing.db").string()}, 1, "no such store"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_knoblab(c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.says << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "missing.db"));
}

// A store as knoblab left it at schema version 6, made by SQL: results from
// then have no provenance, and say so.
TEST(ResultsCliOldStore, ResultsStoredBeforeSchema7ShowNoProvenanceAndKeepTheirFiles) {
  ScratchDir dir;
  const auto db = (dir / "old.db").string();
  {
    auto c = store::sqlite::Connection::open(db);
    c.exec("PRAGMA foreign_keys = ON");
    store::migrate(c, 6);
    c.exec(R"sql(
INSERT INTO captures (id, mode, rate_hz, source, status, sample_count)
  VALUES (1, 'lab', 1000, 'import', 'complete', 0), (2, 'lab', 1000, 'import', 'complete', 0);
INSERT INTO fits (id, capture_id, model, params, result, created_at)
  VALUES (4, 1, 'thesis6', '{}', '{"rmse_Nm":0.002,"detents":{"per_rev":12.0}}', '2024-05-01T10:00:00.000Z');
INSERT INTO fit_files (fit_id, name, bytes) VALUES (4, 'fit.json', x'7b7d0a'), (4, 'a.png', x'8950');
INSERT INTO discrepancies (id, capture_id, heldout_capture_id, result, created_at)
  VALUES (3, 2, 1, '{"base":{"heldout_rmse_Nm":0.00957},"final":{"heldout_rmse_Nm":0.0015},"findings":[{},{}]}',
          '2024-04-01T10:00:00.000Z');
)sql");
  }
  RunResult r = run_knoblab({"results", "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "kind             id  capture  created                   version                   files  key figure\n"
            "discrepancy       3        2  2024-04-01T10:00:00.000Z  -                             0  held-out rms 9.57 → 1.5 mN·m, 2 findings\n"
            "fit               4        1  2024-05-01T10:00:00.000Z  -                             2  rmse 2 mN·m, 12.00 detents/rev\n");
  EXPECT_EQ(store::Store::open(db).schema_version(), store::latest_schema_version());  // upgraded on the way

  r = run_knoblab({"fits", "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("    2  -                         -\n"), std::string::npos) << r.out;

  r = run_knoblab({"results", "3", "--kind", "discrepancy", "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  held out:  capture 1\n  provenance: none (stored before knoblab kept it)\n"),
            std::string::npos)
      << r.out;
  r = run_knoblab({"results", "4", "--kind", "fit", "--db", db, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["tool_version"].is_null());
  EXPECT_TRUE(j["input_sha256"].is_null());
  EXPECT_TRUE(j["options"].is_null());
  EXPECT_EQ(j["files"], 2);
  EXPECT_EQ(j["report"].size(), 2u);
}

TEST(CliVersion, TheVersionNamesTheCommitBuiltAndWhetherTheTreeDifferedFromIt) {
  // What a stored result's provenance carries: a release number alone would
  // say the same for every build.
  EXPECT_TRUE(std::regex_match(knoblab::kVersion, std::regex(R"(\d+\.\d+\.\d+\+(g[0-9a-f]{12}(\.dirty)?|unknown))")))
      << knoblab::kVersion;
}

TEST(CliVersion, KnoblabAndEveryCommandPrintTheProjectVersion) {
  const std::string expected = std::string("knoblab ") + knoblab::kVersion + "\n";
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--version"}, {"fit", "--version"}, {"results", "--version"}, {"simulate", "--version"}}) {
    const RunResult r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, 0) << args[0];
    EXPECT_EQ(r.out, expected) << args[0];
    EXPECT_EQ(r.err, "");
  }
}

}  // namespace
}  // namespace knoblab::test
