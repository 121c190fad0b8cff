// Import keeps what a file's metadata says: order, repeated keys, free
// comments; text that is not UTF-8 or not one line is refused clearly.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "process.hpp"

namespace knoblab::test {
namespace {

const char* kRows = "t,theta,torque\n0,0,0\n0.001,0.001,0.001\n0.002,0.002,0.002\n";

// The capture's stored metadata object, as export writes it.
nlohmann::ordered_json stored_metadata(const ScratchDir& dir, const std::string& db) {
  const auto out = dir / "back.csv";
  const RunResult r = run_knoblab({"export", "1", "--db", db, "--out", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_file(out);
  const auto at = text.find("# metadata: ");
  if (at == std::string::npos) return {};
  const auto end = text.find('\n', at);
  return nlohmann::ordered_json::parse(text.substr(at + 12, end - at - 12));
}

TEST(ImportMetadata, KeysKeepTheirOrderAndRepeatedKeysAndFreeCommentsAreAllKept) {
  ScratchDir dir;
  const auto csv = dir / "k.csv";
  write_file(csv, "# zeta: last letter\n# alpha: first letter\n# note: one\n# a free comment\n# note: two\n"
                  "# another free comment\n" + std::string(kRows));
  const auto db = (dir / "s.sqlite").string();
  const RunResult r = run_knoblab({"import", csv.string(), "--db", db});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = stored_metadata(dir, db);
  std::vector<std::string> keys;
  for (const auto& [k, v] : m.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"zeta", "alpha", "note", "comments"}));
  EXPECT_EQ(m["note"], nlohmann::ordered_json::array({"one", "two"}));
  EXPECT_EQ(m["comments"], nlohmann::ordered_json::array({"a free comment", "another free comment"}));

  // Exported and imported again, the same metadata, and where it came from.
  const auto again = (dir / "again.sqlite").string();
  ASSERT_EQ(run_knoblab({"import", (dir / "back.csv").string(), "--db", again}).exit_code, 0);
  auto m2 = stored_metadata(dir, again);
  EXPECT_EQ(m2["exported_from"]["capture_id"], "1") << m2;
  EXPECT_EQ(m2["exported_from"]["status"], "complete") << m2;
  m2.erase("exported_from");
  EXPECT_EQ(m2, m);
}

TEST(ImportMetadata, MetadataThatIsNotUtf8IsRefusedNamingTheLine) {
  ScratchDir dir;
  const auto csv = dir / "latin1.csv";
  write_file(csv, "# knob: fan\n# operator: J\xfcrgen\n" + std::string(kRows));
  const RunResult r = run_knoblab({"import", csv.string(), "--db", (dir / "s.sqlite").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("latin1.csv:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not valid UTF-8"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
}

TEST(ImportMetadata, AKnobNameWithAControlCharacterIsRefusedAndNothingIsStored) {
  ScratchDir dir;
  const auto csv = dir / "k.csv";
  write_file(csv, kRows);
  const auto db = (dir / "s.sqlite").string();
  ASSERT_EQ(run_knoblab({"import", csv.string(), "--db", db, "--knob", "plain"}).exit_code, 0);
  const RunResult r = run_knoblab({"import", csv.string(), "--db", db, "--knob", "fan\x1b[31m red"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("control character"), std::string::npos) << r.err;
  const RunResult list = run_knoblab({"list", "--db", db, "--json"});
  EXPECT_EQ(nlohmann::json::parse(list.out).size(), 1u) << list.out;
}

}  // namespace
}  // namespace knoblab::test
