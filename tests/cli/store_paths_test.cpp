// A mistyped --db never creates a store: commands that read or add to one
// say there is no such store, exit non-zero and leave no file behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "process.hpp"

namespace knoblab::test {
namespace {

TEST(StorePaths, NoCommandThatReadsOrAddsToAStoreCreatesOneWhereThePathIsWrong) {
  ScratchDir dir;
  const std::string db = (dir / "mistyped.sqlite").string();
  const std::vector<std::vector<std::string>> commands = {
      {"list", "--db", db},
      {"export", "1", "--out", (dir / "out.csv").string(), "--db", db},
      {"inspect", "--capture", "1", "--db", db},
      {"fits", "--db", db},
      {"fit-export", "1", "--json", "-", "--db", db},
      {"fit", "--capture", "1", "--db", db},
      {"discrepancy", "--capture", "1", "--db", db},
  };
  for (const auto& args : commands) {
    const RunResult r = run_knoblab(args);
    EXPECT_NE(r.exit_code, 0) << args[0];
    EXPECT_NE(r.err.find("no such store"), std::string::npos) << args[0] << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(db)) << args[0] << " created " << db;
  }
}

}  // namespace
}  // namespace knoblab::test
