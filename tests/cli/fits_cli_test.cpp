// knoblab fits / fit-export end to end: a store filled by `knoblab simulate`,
// fits with report files inserted through the Store API, then the real binary.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "knoblab/store/store.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

std::vector<std::uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }
std::string text_of(const std::vector<std::uint8_t>& bytes) { return {bytes.begin(), bytes.end()}; }

// A PNG-looking blob with every byte value, zeros and a trailing zero run.
std::vector<std::uint8_t> binary_blob() {
  std::vector<std::uint8_t> b = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13};
  for (int round = 0; round < 4; ++round)
    for (int v = 255; v >= 0; --v) b.push_back(static_cast<std::uint8_t>(v));
  b.insert(b.end(), 9, 0);
  return b;
}

// Shaped like fit::to_json (apps/fit/include/knoblab/fit/result_json.hpp).
const std::string kResultA = R"({
  "model": "thesis6",
  "params": {
    "M_acc": 1.2e-05,
    "P_pos": 0.08333
  },
  "detents": {
    "present": true,
    "per_rev": 12.00048001920077,
    "power": 0.91,
    "false_alarm": 0.0
  },
  "stick": null,
  "rmse_Nm": 0.000123456,
  "fit_percent": 93.456,
  "bic": -12345.6,
  "samples": 20000
})";
const std::string kResultB =
    R"({"model":"render4","detents":{"present":false,"per_rev":null},"rmse_Nm":0.0021,"fit_percent":71.04})";

struct Files {
  std::vector<store::FitFile> a;  // fit 1's report
  std::vector<store::FitFile> c;  // fit 3's one file
};

Files report_files() {
  Files f;
  f.a = {{"fit.json", bytes_of(kResultA + "\n")},
         {"torque_vs_theta.png", binary_blob()},
         {"residuals.svg", bytes_of("<svg xmlns=\"http://www.w3.org/2000/svg\"/>\n")},
         {"render_model.json", bytes_of(R"({"model":"render4","params":{}})" "\n")},
         {"empty.txt", {}}};
  f.c = {{"notes.txt", bytes_of("old fit, no figures")}};
  return f;
}

class FitsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = (dir_ / "k.db").string();
    RunResult r = run_knoblab(
        {"simulate", "--knob", "moderate-detents", "--seconds", "2", "--db", db_});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_knoblab({"simulate", "--knob", "subtle-detents", "--seconds", "0.5", "--db", db_});
    ASSERT_EQ(r.exit_code, 0) << r.err;

    auto store = store::Store::open(db_);
    const auto captures = store.list_captures();
    ASSERT_EQ(captures.size(), 2u);
    ASSERT_EQ(captures[0].id, 1);
    ASSERT_EQ(captures[1].id, 2);
    const Files files = report_files();
    ASSERT_EQ(store.insert_fit(1, "thesis6", R"({"model":"thesis6"})", kResultA, files.a), 1);
    ASSERT_EQ(store.insert_fit(2, "render4", R"({"model":"render4"})", kResultB), 2);
    ASSERT_EQ(store.insert_fit(1, "thesis6", "{}", "{}", files.c), 3);
    for (std::int64_t id = 1; id <= 3; ++id) created_.push_back(store.fit_info(id)->created_at);
    ASSERT_EQ(created_[0].size(), 24u) << created_[0];  // 2025-01-02T03:04:05.678Z
  }

  ScratchDir dir_;
  std::string db_;
  std::vector<std::string> created_;  // of fits 1, 2, 3
};

const char* const kHeader =
    "    id  capture  model    created                     rmse_Nm  fit_% detents/rev files  version                   input\n";

TEST_F(FitsCli, ListsEveryFitWithItsKeyFigures) {
  const RunResult r = run_knoblab({"fits", "--db", db_});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, std::string(kHeader) +
                       "     1        1  thesis6  " + created_[0] + "  0.0001235   93.5       12.00     5  -                         -\n"
                       "     2        2  render4  " + created_[1] + "     0.0021   71.0           -     0  -                         -\n"
                       "     3        1  thesis6  " + created_[2] + "          -      -           -     1  -                         -\n");
}

TEST_F(FitsCli, ListsTheFitsOfOneCapture) {
  RunResult r = run_knoblab({"fits", "--db", db_, "--capture", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, std::string(kHeader) + "     2        2  render4  " + created_[1] +
                       "     0.0021   71.0           -     0  -                         -\n");
  r = run_knoblab({"fits", "--db", db_, "--capture", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\n     1        1  thesis6"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n     3        1  thesis6"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("render4"), std::string::npos) << r.out;
}

TEST_F(FitsCli, ListErrors) {
  RunResult r = run_knoblab({"fits", "--db", db_, "--capture", "99"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("no capture 99 in the store"), std::string::npos) << r.err;
  r = run_knoblab({"fits", "--db", db_, "--capture", "one"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--capture must be a capture id"), std::string::npos) << r.err;
  r = run_knoblab({"fits"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("needs --db"), std::string::npos) << r.err;
  r = run_knoblab({"fits", "--db", db_, "7"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unexpected argument '7'"), std::string::npos) << r.err;
}

TEST_F(FitsCli, ExportWritesTheResultAndEveryFileByteForByte) {
  const auto out = dir_ / "fit1.json";
  const auto report = dir_ / "report" / "fit1";  // created, parents too
  const RunResult r = run_knoblab(
      {"fit-export", "1", "--db", db_, "--json", out.string(), "--report", report.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::size_t total = [] {
    std::size_t n = 0;
    for (const auto& f : report_files().a) n += f.bytes.size();
    return n;
  }();
  EXPECT_EQ(r.out, "fit 1: result JSON written to " + out.string() + "\n" +
                       "fit 1: 5 report files (" + std::to_string(total) + " bytes) written to " +
                       report.string() + "\n");
  EXPECT_EQ(read_file(out), kResultA + "\n");

  std::set<std::string> written;
  for (const auto& e : std::filesystem::directory_iterator(report))
    written.insert(e.path().filename().string());
  std::set<std::string> stored;
  for (const auto& f : report_files().a) {
    stored.insert(f.name);
    EXPECT_EQ(read_file(report / f.name), text_of(f.bytes)) << f.name;
    EXPECT_EQ(std::filesystem::file_size(report / f.name), f.bytes.size()) << f.name;
  }
  EXPECT_EQ(written, stored);
}

TEST_F(FitsCli, ExportJsonToStdoutIsExactlyTheStoredResult) {
  RunResult r = run_knoblab({"fit-export", "2", "--db", db_, "--json", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, kResultB + "\n");
  EXPECT_EQ(r.err, "");
  // With --report too, stdout stays pure JSON.
  r = run_knoblab({"fit-export", "3", "--db", db_, "--json", "-", "--report", (dir_ / "r3").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "{}\n");
  EXPECT_EQ(read_file(dir_ / "r3" / "notes.txt"), "old fit, no figures");
}

TEST_F(FitsCli, ExportOverwritesStaleFilesAndKeepsOthers) {
  const auto report = dir_ / "report";
  std::filesystem::create_directories(report);
  write_file(report / "fit.json", std::string(100000, 'x'));  // longer than the stored one
  write_file(report / "mine.txt", "keep me");
  const RunResult r = run_knoblab({"fit-export", "1", "--db", db_, "--report", report.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_file(report / "fit.json"), kResultA + "\n");
  EXPECT_EQ(read_file(report / "mine.txt"), "keep me");
}

TEST_F(FitsCli, ExportErrors) {
  const auto out = dir_ / "out.json";
  const auto report = dir_ / "report";
  RunResult r = run_knoblab(
      {"fit-export", "99", "--db", db_, "--json", out.string(), "--report", report.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("knoblab fit-export: error: no fit 99 in the store"), std::string::npos)
      << r.err;
  // A fit without report files: nothing is written, not even the JSON.
  r = run_knoblab({"fit-export", "2", "--db", db_, "--json", out.string(), "--report",
                   report.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("fit 2 has no stored report files"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(report));

  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"fit-export", "abc", "--db", db_, "--json", "-"},
           {"fit-export", "0", "--db", db_, "--json", "-"},
           {"fit-export", "1", "--db", db_},
           {"fit-export", "--db", db_, "--json", "-"},
           {"fit-export", "1", "--json", "-"},
           {"fit-export", "1", "2", "--db", db_, "--json", "-"}}) {
    r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, 2) << args[1] << ": " << r.err;
    EXPECT_NE(r.err.find("try 'knoblab fit-export --help'"), std::string::npos) << r.err;
  }
  r = run_knoblab({"fit-export", "abc", "--db", db_, "--json", "-"});
  EXPECT_NE(r.err.find("FIT must be a fit id (a positive integer), got 'abc'"), std::string::npos)
      << r.err;
  r = run_knoblab({"fit-export", "1", "--db", db_});
  EXPECT_NE(r.err.find("--json"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(FitsCliHelp, CommandsAreListedAndHaveHelp) {
  const RunResult overview = run_knoblab({"--help"});
  EXPECT_EQ(overview.exit_code, 0);
  EXPECT_NE(overview.out.find("\n  fits        List the stored fits"), std::string::npos)
      << overview.out;
  EXPECT_NE(overview.out.find("\n  fit-export  Write a stored fit's result JSON"), std::string::npos)
      << overview.out;
  for (const char* c : {"fits", "fit-export"}) {
    const RunResult r = run_knoblab({c, "--help"});
    EXPECT_EQ(r.exit_code, 0) << c;
    EXPECT_NE(r.out.find(std::string("usage: knoblab ") + c + " "), std::string::npos) << r.out;
  }
}

}  // namespace
}  // namespace knoblab::test
