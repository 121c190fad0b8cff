// Every malformed input the reader must reject, with line and column.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <streambuf>

#include "knoblab/interchange/csv.hpp"

namespace ki = knoblab::interchange;
using ::testing::HasSubstr;

namespace {

struct Caught {
  std::size_t line = 0, column = 0;
  std::string what;
};

Caught parse_error(std::istream& in) {
  try {
    ki::parse_csv(in, "k.csv");
  } catch (const ki::CsvError& e) {
    return {e.line(), e.column(), e.what()};
  }
  ADD_FAILURE() << "parse_csv accepted bad input";
  return {};
}

Caught parse_error(const std::string& text) {
  std::istringstream in(text);
  return parse_error(in);
}

const std::string kHeader = "t,theta,torque\n";

// An endless-looking input: `total` bytes from gen(i), generated on demand,
// so a test can check how much of it the parser actually consumed.
class GeneratedBuf : public std::streambuf {
 public:
  GeneratedBuf(std::uint64_t total, char (*gen)(std::uint64_t)) : total_(total), gen_(gen) {}
  std::uint64_t produced() const { return produced_; }

 protected:
  int_type underflow() override {
    if (produced_ >= total_) return traits_type::eof();
    const auto n =
        static_cast<std::size_t>(std::min<std::uint64_t>(buf_.size(), total_ - produced_));
    for (std::size_t i = 0; i < n; ++i) buf_[i] = gen_(produced_ + i);
    produced_ += n;
    setg(buf_.data(), buf_.data(), buf_.data() + n);
    return traits_type::to_int_type(buf_[0]);
  }

 private:
  std::array<char, 4096> buf_{};
  std::uint64_t produced_ = 0, total_;
  char (*gen_)(std::uint64_t);
};

constexpr std::uint64_t kGiB = 1ull << 30;
constexpr std::uint64_t kEarly = 256 * 1024;  // "rejected early" means within this

}  // namespace

TEST(CsvError, MessageNamesSourceLineAndColumn) {
  const auto e = parse_error(kHeader + "0,0,0\n1,1,abc\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_EQ(e.column, 3u);
  EXPECT_EQ(e.what, "k.csv:3:3: column 'torque': not a number: \"abc\"");
}

TEST(CsvError, MissingRequiredColumnNamesIt) {
  auto e = parse_error("t,theta,omega\n0,0,0\n1,1,1\n2,2,2\n");
  EXPECT_EQ(e.line, 1u);
  EXPECT_EQ(e.column, 0u);
  EXPECT_THAT(e.what, HasSubstr("missing required column 'torque'"));
  e = parse_error("# a: b\ntorque\n0\n1\n2\n");
  EXPECT_EQ(e.line, 2u);
  EXPECT_THAT(e.what, HasSubstr("missing required columns 't', 'theta'"));
}

TEST(CsvError, DuplicateColumn) {
  const auto e = parse_error("t,theta,torque,theta\n0,0,0,0\n");
  EXPECT_EQ(e.line, 1u);
  EXPECT_EQ(e.column, 4u);
  EXPECT_THAT(e.what, HasSubstr("duplicate column 'theta' (also column 2)"));
}

TEST(CsvError, UnknownColumnNamesItAndListsAllowed) {
  const auto e = parse_error("t,angle,torque\n");
  EXPECT_EQ(e.line, 1u);
  EXPECT_EQ(e.column, 2u);
  EXPECT_THAT(e.what, HasSubstr("unknown column \"angle\""));
  EXPECT_THAT(e.what, HasSubstr("allowed: t, theta, omega, alpha, torque, command"));
}

TEST(CsvError, ColumnNamesAreCaseSensitive) {
  EXPECT_THAT(parse_error("t,Theta,torque\n").what, HasSubstr("unknown column \"Theta\""));
}

TEST(CsvError, EmptyColumnName) {
  const auto e = parse_error("t,theta,torque,\n");
  EXPECT_EQ(e.column, 4u);
  EXPECT_THAT(e.what, HasSubstr("empty column name"));
}

TEST(CsvError, DataWhereHeaderExpected) {
  const auto e = parse_error("0,0,0\n1,1,1\n2,2,2\n");
  EXPECT_EQ(e.line, 1u);
  EXPECT_THAT(e.what, HasSubstr("expected a header line"));
}

TEST(CsvError, EmptyFile) {
  auto e = parse_error("");
  EXPECT_EQ(e.line, 1u);
  EXPECT_THAT(e.what, HasSubstr("empty file"));
}

TEST(CsvError, OnlyCommentsNoHeader) {
  const auto e = parse_error("# knob: x\n\n# rate: 1\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_THAT(e.what, HasSubstr("no header line"));
}

TEST(CsvError, NanAndInfRejected) {
  for (const char* bad : {"nan", "NaN", "-nan", "inf", "-inf", "Infinity"}) {
    const auto e = parse_error(kHeader + "0,0,0\n1," + bad + ",1\n2,2,2\n");
    EXPECT_EQ(e.line, 3u) << bad;
    EXPECT_EQ(e.column, 2u) << bad;
    EXPECT_THAT(e.what, HasSubstr("column 'theta': not finite")) << bad;
  }
}

TEST(CsvError, OutOfDoubleRange) {
  const auto e = parse_error(kHeader + "0,1e999,0\n");
  EXPECT_EQ(e.column, 2u);
  EXPECT_THAT(e.what, HasSubstr("out of double range"));
}

TEST(CsvError, NonNumericFields) {
  for (const char* bad : {"abc", "1.0.0", "0x10", "1,5e", "--1", "\"1\"", "1 2", "++1"}) {
    const auto e = parse_error(kHeader + "0,0," + bad + "\n");
    EXPECT_EQ(e.line, 2u) << bad;
    EXPECT_THAT(e.what, ::testing::AnyOf(HasSubstr("not a number"), HasSubstr("too many fields")))
        << bad;
  }
}

TEST(CsvError, EmptyField) {
  const auto e = parse_error(kHeader + "0,,0\n");
  EXPECT_EQ(e.column, 2u);
  EXPECT_THAT(e.what, HasSubstr("column 'theta': empty field"));
}

TEST(CsvError, NonIncreasingTimeNamesTheLines) {
  auto e = parse_error(kHeader + "0,0,0\n0.001,0,0\n0.001,0,0\n");
  EXPECT_EQ(e.line, 4u);
  EXPECT_EQ(e.column, 1u);
  EXPECT_THAT(e.what, HasSubstr("not strictly increasing: 0.001 at line 4 after 0.001 at line 3"));
  e = parse_error("theta,torque,t\n0,0,1\n0,0,0.5\n0,0,2\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_EQ(e.column, 3u);
}

TEST(CsvError, SemicolonDelimiter) {
  const auto e = parse_error("t;theta;torque\n0;0;0\n");
  EXPECT_EQ(e.line, 1u);
  EXPECT_THAT(e.what, HasSubstr("expected ',' delimiter, found ';'"));
}

TEST(CsvError, TabDelimiter) {
  const auto e = parse_error("t\ttheta\ttorque\n0\t0\t0\n");
  EXPECT_EQ(e.line, 1u);
  EXPECT_THAT(e.what, HasSubstr("expected ',' delimiter, found '\\t'"));
}

TEST(CsvError, SemicolonInDataRows) {
  const auto e = parse_error(kHeader + "0,0,0\n1;1;1\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_THAT(e.what, HasSubstr("expected ',' delimiter, found ';'"));
}

TEST(CsvError, TruncatedLine) {
  const auto e = parse_error(kHeader + "0,0,0\n1,1\n2,2,2\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_EQ(e.column, 0u);
  EXPECT_THAT(e.what, HasSubstr("truncated line: expected 3 fields, found 2"));
}

TEST(CsvError, TooManyFields) {
  const auto e = parse_error(kHeader + "0,0,0\n1,1,1,1\n2,2,2\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_EQ(e.column, 4u);
  EXPECT_THAT(e.what, HasSubstr("too many fields: expected 3, found 4"));
}

TEST(CsvError, FewerThanThreeRows) {
  auto e = parse_error(kHeader + "0,0,0\n1,1,1\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_THAT(e.what, HasSubstr("need at least 3 data rows, found 2"));
  EXPECT_THAT(parse_error(kHeader).what, HasSubstr("found 0"));
}

TEST(CsvError, EmptyLineInsideData) {
  const auto e = parse_error(kHeader + "0,0,0\n\n1,1,1\n2,2,2\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_THAT(e.what, HasSubstr("empty line inside the data"));
}

TEST(CsvError, CommentAfterHeader) {
  const auto e = parse_error(kHeader + "0,0,0\n# late: 1\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_THAT(e.what, HasSubstr("before the header"));
}

TEST(CsvError, BareCarriageReturns) {
  const auto e = parse_error("t,theta,torque\r0,0,0\r1,1,1\r2,2,2\r");
  EXPECT_EQ(e.line, 1u);
  EXPECT_THAT(e.what, HasSubstr("carriage return"));
}

TEST(CsvError, NulByteNamesFieldAndLine) {
  const auto e = parse_error(kHeader + "0,0,0\n1,1" + std::string(1, '\0') + ",1\n");
  EXPECT_EQ(e.line, 3u);
  EXPECT_EQ(e.column, 2u);
  EXPECT_THAT(e.what, HasSubstr("control byte 0x00"));
}

TEST(CsvError, GigabyteOfBinaryRejectedEarly) {
  GeneratedBuf buf(kGiB, [](std::uint64_t i) {
    // Deterministic noise over all 256 byte values.
    return static_cast<char>((i * 2654435761u) >> 13);
  });
  std::istream in(&buf);
  const auto e = parse_error(in);
  EXPECT_THAT(e.what, HasSubstr("control byte"));
  EXPECT_LT(buf.produced(), kEarly);
}

TEST(CsvError, GigabyteLineRejectedEarly) {
  GeneratedBuf buf(kGiB, [](std::uint64_t) { return 'x'; });
  std::istream in(&buf);
  const auto e = parse_error(in);
  EXPECT_EQ(e.line, 1u);
  EXPECT_THAT(e.what, HasSubstr("line longer than 65536 bytes"));
  EXPECT_LT(buf.produced(), kEarly);
}

TEST(CsvError, LongLineAfterHeaderRejected) {
  std::string text = kHeader + "0,0,0\n1,1," + std::string(70000, '1') + "\n";
  const auto e = parse_error(text);
  EXPECT_EQ(e.line, 3u);
  EXPECT_THAT(e.what, HasSubstr("line longer than"));
}

TEST(CsvError, LineOfExactlyTheLimitIsNotTooLong) {
  // 64 KiB of spaces and a number is odd but legal: the limit is exclusive.
  const std::string pad(ki::kMaxLineBytes - 5, ' ');
  std::string text = kHeader + "0,0,0\n1,1,1\n2,2," + pad + "2\r\n";
  std::istringstream in(text);
  EXPECT_EQ(ki::parse_csv(in, "k.csv").size(), 3u);
}

TEST(CsvError, GigabyteOfCommentsRejectedEarly) {
  GeneratedBuf buf(kGiB, [](std::uint64_t i) { return i % 10 == 9 ? '\n' : '#'; });
  std::istream in(&buf);
  const auto e = parse_error(in);
  EXPECT_THAT(e.what, HasSubstr("no header line within"));
  EXPECT_LT(buf.produced(), ki::kMaxMetadataBytes + kEarly);
}

TEST(CsvError, GigabyteOfEmptyLinesAfterDataRejectedEarly) {
  static const std::string head = kHeader + "0,0,0\n1,1,1\n2,2,2\n";
  GeneratedBuf buf(kGiB, [](std::uint64_t i) { return i < head.size() ? head[i] : '\n'; });
  std::istream in(&buf);
  const auto e = parse_error(in);
  EXPECT_THAT(e.what, HasSubstr("too many empty lines"));
  EXPECT_LT(buf.produced(), kEarly);
}

TEST(CsvError, SparseGigabyteFileRejectedEarly) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("knoblab_garbage_" + std::to_string(::getpid()) + ".csv");
  {
    std::ofstream out(path);
  }
  std::filesystem::resize_file(path, kGiB);  // sparse: a gigabyte of NUL bytes
  try {
    ki::read_csv(path);
    ADD_FAILURE() << "accepted";
  } catch (const ki::CsvError& e) {
    EXPECT_EQ(e.line(), 1u);
    EXPECT_THAT(std::string(e.what()), HasSubstr("control byte 0x00"));
  }
  std::filesystem::remove(path);
}

TEST(CsvError, MissingFile) {
  try {
    ki::read_csv("/nonexistent/k.csv");
    ADD_FAILURE() << "accepted";
  } catch (const ki::CsvError& e) {
    EXPECT_EQ(e.line(), 0u);
    EXPECT_THAT(std::string(e.what()), HasSubstr("/nonexistent/k.csv: cannot open"));
  }
}

namespace {

TEST(CsvMagnitude, AFiniteButHugeValueIsRefusedWithItsLineAndColumn) {
  const Caught c = parse_error(kHeader + "0,0,0\n0.001,1e300,0\n0.002,0,0\n");
  EXPECT_EQ(c.line, 3u);
  EXPECT_EQ(c.column, 2u);
  EXPECT_THAT(c.what, HasSubstr("column 'theta': \"1e300\" is beyond ±1e12"));
}

TEST(CsvMagnitude, ADerivedChannelThatOverflowsNamesTheLineAndWhereItCameFrom) {
  // Finite, in range and increasing, but 1e-290 s apart: θ̇ = 1/1e-290.
  const Caught c = parse_error(kHeader + "0,0,0\n1e-290,1,0\n1,2,0\n2,3,0\n");
  EXPECT_GE(c.line, 2u);
  EXPECT_LE(c.line, 3u);
  EXPECT_THAT(c.what, HasSubstr("omega (not in the file, derived from theta and t) is beyond ±1e12"));
}

}  // namespace
