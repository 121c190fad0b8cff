// Result files are replaced whole or not at all: a write that fails part way
// (here the file-size limit, as a full disk would) leaves the previous file
// in place and no temporary file behind, and says why.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "process.hpp"

namespace knoblab::test {
namespace {

// knoblab under `ulimit -f KB` with SIGXFSZ ignored: a write past KB KiB in
// any file fails with EFBIG, the way a full disk fails it with ENOSPC. Its stdout and
// stderr go through pipes (the limit holds for every regular file, the
// test's capture files too), copied to those files by unlimited cats.
RunResult run_without_room(const ScratchDir& dir, int kb, const std::vector<std::string>& args) {
  const std::string script = "set -o pipefail; { ( ulimit -f " + std::to_string(kb) +
                             "; trap '' XFSZ; exec \"$@\" ) 2>&1 1>&3 3>&- | cat >&2; } 3>&1 | cat";
  std::vector<std::string> argv = {"/bin/bash", "-c", script, "bash", KNOBLAB_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  const std::string out = (dir / "stdout").string(), err = (dir / "stderr").string();
  const pid_t pid = spawn(argv, out, err);
  const auto code = wait_exit(pid, std::chrono::seconds(120));
  RunResult r;
  r.exit_code = code.value_or(-2);
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

std::vector<std::string> leftovers(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) names.push_back(e.path().string());
  return names;
}

class ResultFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    csv_ = (dir_ / "knob.csv").string();
    const RunResult sim = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "3", "--out", csv_});
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
  }
  ScratchDir dir_;
  std::string csv_;
};

TEST_F(ResultFiles, AFitJsonOrRenderModelThatCannotBeWrittenLeavesThePreviousFile) {
  for (const std::string option : {"--json", "--render-model"}) {
    const auto out = dir_ / "previous.json";
    write_file(out, "{\"previous\": true}\n");
    const RunResult r = run_without_room(dir_, 0, {"fit", "--input", csv_, option, out.string()});
    EXPECT_NE(r.exit_code, 0) << option;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << option << ": " << r.err;
    EXPECT_EQ(read_file(out), "{\"previous\": true}\n") << option;
    EXPECT_TRUE(leftovers(dir_.path()).empty()) << option;
  }
}

TEST_F(ResultFiles, AReportPlotThatCannotBeWrittenLeavesThePreviousPlot) {
  const auto report = dir_ / "report";
  std::filesystem::create_directory(report);
  write_file(report / "torque_position.png", "previous");
  // Room for PLplot's own temporary driver list, not for a plot.
  const RunResult r = run_without_room(dir_, 32, {"fit", "--input", csv_, "--report", report.string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("torque_position"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(report / "torque_position.png"), "previous");
  EXPECT_TRUE(leftovers(report).empty());
}

TEST_F(ResultFiles, AWholeResultReplacesThePreviousFile) {
  const auto out = dir_ / "fit.json";
  write_file(out, "{\"previous\": true}\n");
  const RunResult r = run_knoblab({"fit", "--input", csv_, "--json", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_file(out).find("\"model\": \"thesis6\""), std::string::npos);
  EXPECT_TRUE(leftovers(dir_.path()).empty());
}

}  // namespace
}  // namespace knoblab::test
