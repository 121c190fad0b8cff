// knoblab discrepancy on a capture from the store: the result is stored
// beside it, the same bytes --json writes, with the held-out capture's id
// when one was held out whole.
#include <gtest/gtest.h>

#include <string>

#include "knoblab/store/store.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

class DiscrepancyStoreCli : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = (dir_ / "k.db").string();
    // Two recordings of one knob: capture 1 and capture 2.
    for (int i = 0; i < 2; ++i) {
      const RunResult r =
          run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "4", "--db", db_});
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    auto store = store::Store::open(db_);
    ASSERT_EQ(store.list_captures().size(), 2u);
  }

  std::int64_t rows() {
    return store::Store::open(db_).connection().query_int("SELECT count(*) FROM discrepancies");
  }

  ScratchDir dir_;
  std::string db_;
};

TEST_F(DiscrepancyStoreCli, StoresOneRowWhoseResultIsWhatJsonWrote) {
  const auto json = dir_ / "r.json";
  const RunResult r = run_knoblab({"discrepancy", "--capture", "1", "--db", db_, "--json", json.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("capture 1 (moderate-detents): "), std::string::npos) << r.out;
  // The last line, after the figures.
  const std::string stored_line = "\nstored as discrepancy 1\n";
  ASSERT_GE(r.out.size(), stored_line.size());
  EXPECT_EQ(r.out.substr(r.out.size() - stored_line.size()), stored_line) << r.out;

  auto store = store::Store::open(db_);
  EXPECT_EQ(store.connection().query_int("SELECT count(*) FROM discrepancies"), 1);
  const auto listed = store.list_discrepancies(1);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].id, 1);
  EXPECT_EQ(listed[0].capture_id, 1);
  EXPECT_FALSE(listed[0].heldout_capture_id);
  EXPECT_EQ(listed[0].result + "\n", read_file(json));  // write_text ends the file with a newline
  EXPECT_NE(listed[0].result.find("\"findings\""), std::string::npos) << listed[0].result;
  EXPECT_TRUE(store.list_discrepancies(2).empty());
}

TEST_F(DiscrepancyStoreCli, TheHeldOutCaptureIsStoredAndJsonToStdoutStaysJsonOnly) {
  const RunResult r = run_knoblab(
      {"discrepancy", "--capture", "1", "--heldout-capture", "2", "--db", db_, "--json", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("stored as"), std::string::npos) << r.out;

  auto store = store::Store::open(db_);
  const auto listed = store.list_discrepancies(1);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].heldout_capture_id, 2);
  EXPECT_EQ(listed[0].result + "\n", r.out);  // stdout is the JSON and nothing else

  // Deleting the held-out recording keeps the result, no longer pointing at it.
  store.delete_capture(2);
  const auto kept = store.discrepancy_info(listed[0].id);
  ASSERT_TRUE(kept);
  EXPECT_FALSE(kept->heldout_capture_id);
  EXPECT_EQ(kept->result, listed[0].result);
}

TEST_F(DiscrepancyStoreCli, EachRunAddsARowAndACsvInputAddsNone) {
  const auto csv = dir_ / "c.csv";
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "4", "--out",
                         csv.string()}).exit_code, 0);
  RunResult r = run_knoblab({"discrepancy", "--input", csv.string(), "--max-findings", "0"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("stored as"), std::string::npos) << r.out;
  EXPECT_EQ(rows(), 0);
  for (const char* n : {"1", "2"}) {
    r = run_knoblab({"discrepancy", "--capture", "2", "--db", db_, "--max-findings", "0"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(std::string("stored as discrepancy ") + n + "\n"), std::string::npos) << r.out;
  }
  EXPECT_EQ(rows(), 2);
  EXPECT_EQ(store::Store::open(db_).list_discrepancies(2).size(), 2u);
}

}  // namespace
}  // namespace knoblab::test
