// Acceptance: each bad CSV gets a clear error naming file, line and column,
// exits non-zero, and leaves the store exactly as it was.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <random>

#include "../store/test_util.hpp"
#include "knoblab/store/store.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

struct BadCsv {
  const char* name;
  std::string text;
  std::string where;   // "file:line[:column]" suffix expected in the message
  std::string reason;  // phrase expected in the message
};

const std::string kRows = "0,0,0\n0.001,0.1,0.01\n0.002,0.2,0.02\n";

std::vector<BadCsv> bad_files() {
  return {
      {"missing_column", "t,theta\n0,0\n1,1\n2,2\n", ":1", "missing required column 'torque'"},
      {"duplicate_column", "t,theta,torque,theta\n0,0,0,0\n", ":1:4", "duplicate column 'theta'"},
      {"unknown_column", "t,angle,torque\n" + kRows, ":1:2", "unknown column \"angle\""},
      {"empty_file", "", ":1", "empty file"},
      {"nan", "t,theta,torque\n0,0,0\n0.001,nan,0\n0.002,0,0\n", ":3:2", "not finite"},
      {"inf", "t,theta,torque\n0,0,0\n0.001,0,-inf\n0.002,0,0\n", ":3:3", "not finite"},
      {"not_a_number", "t,theta,torque\n0,0,0\n0.001,0,abc\n0.002,0,0\n", ":3:3",
       "column 'torque': not a number: \"abc\""},
      {"t_not_increasing", "t,theta,torque\n0,0,0\n0.001,0,0\n0.001,0,0\n", ":4:1", "not strictly increasing"},
      {"semicolons", "t;theta;torque\n0;0;0\n1;1;1\n2;2;2\n", ":1", "expected ',' delimiter, found ';'"},
      {"tabs", "t\ttheta\ttorque\n0\t0\t0\n1\t1\t1\n2\t2\t2\n", ":1", "expected ',' delimiter, found '\\t'"},
      {"truncated_line", "t,theta,torque\n" + kRows + "0.003,0.3", ":5", "truncated line"},
      {"too_many_fields", "t,theta,torque\n0,0,0\n0.001,0,0,7\n0.002,0,0\n", ":3", "too many fields"},
      {"too_few_rows", "t,theta,torque\n0,0,0\n0.001,0,0\n", "", "need at least 3 data rows"},
      {"long_line", "t,theta,torque\n0,0," + std::string(200000, '7') + "\n", ":2", "line longer than"},
  };
}

class ImportErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = (dir_ / "lab.sqlite").string();
    // Something committed to lose: one capture from the simulator.
    const RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "0.2", "--db", db_});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    before_ = checksum();
  }

  std::string checksum() {
    store::Store s = store::Store::open(db_);
    return store::test::checksum(s.connection());
  }

  void expect_rejected(const std::filesystem::path& file, const std::string& where, const std::string& reason) {
    const RunResult r = run_knoblab({"import", file.string(), "--db", db_});
    EXPECT_EQ(r.exit_code, 1) << file;
    EXPECT_NE(r.err.find(file.string() + where), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
    EXPECT_EQ(checksum(), before_) << "the store changed after importing " << file;
  }

  ScratchDir dir_;
  std::string db_, before_;
};

TEST_F(ImportErrors, EachBadFileIsRefusedAndTheStoreIsUnchanged) {
  for (const BadCsv& bad : bad_files()) {
    SCOPED_TRACE(bad.name);
    const auto file = dir_ / (std::string(bad.name) + ".csv");
    write_file(file, bad.text);
    expect_rejected(file, bad.where, bad.reason);
  }
}

TEST_F(ImportErrors, AGigabyteOfGarbageIsRefusedEarly) {
  // A header, 64 KiB of random bytes, then a sparse hole up to 1 GiB.
  const auto file = dir_ / "garbage.csv";
  std::string bytes = "t,theta,torque\n";
  std::mt19937 rng(42);
  for (int i = 0; i < 65536; ++i) bytes.push_back(static_cast<char>(rng() & 0xff));
  write_file(file, bytes);
  ASSERT_EQ(::truncate(file.c_str(), 1LL << 30), 0);
  expect_rejected(file, ":2", "control byte");
}

TEST_F(ImportErrors, AGoodFileAfterwardsStillImports) {
  const auto file = dir_ / "good.csv";
  write_file(file, "# knob: hand-made\nt,theta,torque\n" + kRows);
  const RunResult r = run_knoblab({"import", file.string(), "--db", db_});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(checksum(), before_);
}

}  // namespace
}  // namespace knoblab::test
