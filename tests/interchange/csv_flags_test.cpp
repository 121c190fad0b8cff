// The optional flags column: each sample's SampleFlag bits, written when a
// capture has any, read back exactly; files without it read as before.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include "knoblab/interchange/csv.hpp"

namespace ki = knoblab::interchange;
using ::testing::HasSubstr;

namespace {

ki::Capture small(std::vector<std::uint32_t> flags) {
  ki::Capture c;
  for (std::size_t i = 0; i < 3; ++i) {
    c.t.push_back(static_cast<double>(i) * 0.5);
    c.theta.push_back(0.25 * static_cast<double>(i));
    c.omega.push_back(1.0);
    c.alpha.push_back(2.0);
    c.torque.push_back(0.125);
  }
  c.flags = std::move(flags);
  return c;
}

std::string csv_text(const ki::Capture& c) {
  std::ostringstream out;
  ki::write_csv(c, out);
  return out.str();
}

ki::Capture parse(const std::string& text) {
  std::istringstream in(text);
  return ki::parse_csv(in, "k.csv");
}

ki::CsvError parse_error(const std::string& text) {
  try {
    parse(text);
  } catch (const ki::CsvError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return ki::CsvError("", 0, 0, "");
}

}  // namespace

TEST(CsvFlags, AreWrittenOnlyWhenSomeSampleHasOne) {
  const std::uint32_t max = std::numeric_limits<std::uint32_t>::max();
  EXPECT_EQ(csv_text(small({0, 5, max})),
            "t,theta,omega,alpha,torque,flags\n"
            "0,0,1,2,0.125,0\n"
            "0.5,0.25,1,2,0.125,5\n"
            "1,0.5,1,2,0.125,4294967295\n");
  // All zero, or none known: the file is what it always was.
  const std::string plain =
      "t,theta,omega,alpha,torque\n0,0,1,2,0.125\n0.5,0.25,1,2,0.125\n1,0.5,1,2,0.125\n";
  EXPECT_EQ(csv_text(small({0, 0, 0})), plain);
  EXPECT_EQ(csv_text(small({})), plain);
}

TEST(CsvFlags, ReadBackExactlyInAnyColumnPosition) {
  const auto c = small({4, 0, 4294967295u});
  EXPECT_EQ(parse(csv_text(c)).flags, c.flags);
  const auto moved = parse("flags,t,theta,torque\n 1 ,0,0,0\n2,1,0,0\n3,2,0,0\n");
  EXPECT_EQ(moved.flags, (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_EQ(moved.theta.size(), 3u);
}

TEST(CsvFlags, FilesWithoutTheColumnStillReadWithNoFlags) {
  const auto c = parse("# knob: fan\nt,theta,torque,command\n0,0,0,0\n1,0,0,0\n2,0,0,0\n");
  EXPECT_TRUE(c.flags.empty());
  EXPECT_TRUE(c.has_command);
  EXPECT_EQ(c.size(), 3u);
}

TEST(CsvFlags, BadFieldsAreRefusedWithLineAndColumn) {
  const std::string head = "t,theta,torque,flags\n0,0,0,1\n";
  struct Case {
    const char* row;
    const char* reason;
  } cases[] = {
      {"1,0,0,-1", "not an unsigned integer"}, {"1,0,0,1.5", "not an unsigned integer"},
      {"1,0,0,+3", "not an unsigned integer"}, {"1,0,0,0x4", "not an unsigned integer"},
      {"1,0,0,abc", "not an unsigned integer"}, {"1,0,0,4294967296", "more than 32 bits"},
      {"1,0,0,", "empty field"},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.row);
    const auto e = parse_error(head + k.row + "\n2,0,0,0\n");
    EXPECT_EQ(e.line(), 3u);
    EXPECT_EQ(e.column(), 4u);
    EXPECT_THAT(e.what(), HasSubstr("column 'flags': "));
    EXPECT_THAT(e.what(), HasSubstr(k.reason));
  }
  const auto dup = parse_error("t,theta,torque,flags,flags\n");
  EXPECT_THAT(dup.what(), HasSubstr("duplicate column 'flags'"));
}

TEST(CsvFlags, ValidateRefusesFlagsOfTheWrongLength) {
  auto c = small({1, 2});
  EXPECT_THROW(ki::validate(c), std::invalid_argument);
  std::ostringstream out;
  EXPECT_THROW(ki::write_csv(c, out), std::invalid_argument);
}
