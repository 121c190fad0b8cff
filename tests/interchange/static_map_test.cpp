// Static maps in the interchange CSV: written and read back exactly, kept
// apart from recordings over time, and refused where they are malformed.
#include <gtest/gtest.h>

#include <numbers>
#include <sstream>

#include "knoblab/interchange/csv.hpp"

namespace knoblab::interchange {
namespace {

std::string error_of(const std::string& text) {
  std::istringstream in(text);
  try {
    parse_recording(in, "m.csv");
  } catch (const CsvError& e) {
    return e.what();
  }
  return "";
}

TEST(StaticMapCsv, WrittenWithItsKindLineAndReadBackBitForBit) {
  StaticMap m;
  m.metadata = {{"source", "a_16.npy:a_16"}, {"positions_per_rev", "8192"}};
  m.theta = {0, 2 * std::numbers::pi * 16 / 8192, 0.1, 6.2};
  m.torque = {0.1 / 3, -1e-9, 0, 0.12};
  std::ostringstream out;
  write_static_map(m, out);
  const std::string head = "# kind: static-map\n# source: a_16.npy:a_16\n# positions_per_rev: 8192\ntheta,torque\n0,0.";
  EXPECT_EQ(out.str().substr(0, head.size()), head);
  std::istringstream in(out.str());
  const Recording r = parse_recording(in, "m.csv");
  ASSERT_TRUE(std::holds_alternative<StaticMap>(r));
  const auto& back = std::get<StaticMap>(r);
  EXPECT_EQ(back.metadata, m.metadata);  // the kind line is structure, not metadata
  EXPECT_EQ(back.theta, m.theta);
  EXPECT_EQ(back.torque, m.torque);
}

TEST(StaticMapCsv, ReadCsvRefusesAMapSayingWhatTakesIt) {
  std::istringstream in("# knob: x\n# kind: static-map\ntheta,torque\n0,1\n1,2\n2,3\n");
  try {
    parse_csv(in, "m.csv");
    FAIL() << "a static map was read as a recording over time";
  } catch (const CsvError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_NE(e.reason().find("a static map (torque over position, no time stamps), not a recording over time: "
                              "'knoblab inspect' reads it"),
              std::string::npos);
  }
}

TEST(StaticMapCsv, ARecordingOverTimeMayNameItsKind) {
  std::istringstream in("# kind: time-series\nt,theta,torque\n0,0,0\n1,1,1\n2,2,2\n");
  const Recording r = parse_recording(in, "r.csv");
  ASSERT_TRUE(std::holds_alternative<Capture>(r));
  EXPECT_TRUE(std::get<Capture>(r).metadata.empty());
}

TEST(StaticMapCsv, MalformedMapsNameLineAndColumn) {
  const std::string kind = "# kind: static-map\n";
  EXPECT_EQ(error_of(kind + "t,theta,torque\n0,0,0\n"),
            "m.csv:2:1: column 't' in a static map (kind line 1): a map holds only theta and torque, no time");
  EXPECT_EQ(error_of(kind + "theta,torque,flags\n"),
            "m.csv:2:3: column 'flags' in a static map (kind line 1): a map holds only theta and torque, no time");
  EXPECT_EQ(error_of(kind + "theta\n"), "m.csv:2: missing required column 'torque' (a static map holds theta and torque)");
  EXPECT_EQ(error_of(kind + "theta,torque\n0,0\n1,0\n1,0\n"),
            "m.csv:5:1: column 'theta': positions not strictly increasing: 1 at line 5 after 1 at line 4");
  EXPECT_EQ(error_of(kind + "torque,theta\n0,0\n0,3\n0,6.3\n"),
            "m.csv:5:2: column 'theta': a static map holds one revolution, these positions span 6.3 rad (2*pi or more)");
  EXPECT_EQ(error_of("# kind: spectrum\nt,theta,torque\n"),
            "m.csv:1: unknown kind \"spectrum\" (time-series, the default, or static-map)");
  EXPECT_EQ(error_of(kind + kind + "theta,torque\n"), "m.csv:2: a second kind line (the first is line 1)");
  EXPECT_EQ(error_of(kind + "theta,torque\n0,0\n1,0\n"), "m.csv:4: need at least 3 data rows, found 2");
}

TEST(StaticMapCsv, WriterRefusesWhatCouldNotBeReadBack) {
  StaticMap m;
  m.theta = {0, 1, 2};
  m.torque = {0, 0, 0};
  m.metadata = {{"kind", "x"}};
  std::ostringstream out;
  EXPECT_THROW(write_static_map(m, out), std::invalid_argument);
  m.metadata.clear();
  m.theta = {0, 3, 6.3};
  EXPECT_THROW(write_static_map(m, out), std::invalid_argument);
  m.theta = {0, 2, 1};
  EXPECT_THROW(write_static_map(m, out), std::invalid_argument);
  EXPECT_TRUE(out.str().empty());
}

}  // namespace
}  // namespace knoblab::interchange
