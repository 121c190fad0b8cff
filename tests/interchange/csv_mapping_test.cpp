// Other tools' CSV through a column mapping: units to SI, delimiters,
// quoting, and errors that name file:line:column.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/mapped_csv.hpp"

namespace knoblab::interchange {
namespace {

constexpr double kPi = std::numbers::pi;

class MappedCsvTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("knoblab-mapped-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path file(const std::string& text) const {
    const auto p = dir_ / "in.csv";
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  std::string error_of(const std::string& text, const std::string& mapping, char delimiter = 0,
                       double counts = 0) const {
    try {
      read_mapped_csv(file(text), parse_column_mapping(mapping, counts), delimiter);
    } catch (const CsvError& e) {
      return std::string(e.what()).substr(dir_.string().size() + 1);  // "in.csv:line:col: ..."
    }
    return "";
  }

  std::filesystem::path dir_;
};

const std::string kMapping = "time_ms=t:ms,angle_deg=theta:deg,torque_mNm=torque:mN*m";

TEST_F(MappedCsvTest, ConvertsEachColumnToSIAndIgnoresTheUnmapped) {
  const MappedCsv m = read_mapped_csv(file("time_ms,angle_deg,torque_mNm,counts\n"
                                           "0,0,1.5,0\n"
                                           "1,90,-2,2048\n"
                                           "2.5,180,0,4096\n"),
                                      parse_column_mapping(kMapping, 0));
  EXPECT_EQ(m.channels[0], (std::vector<double>{0, 1e-3, 2.5e-3}));
  EXPECT_EQ(m.channels[1], (std::vector<double>{0, 90 * (kPi / 180), 180 * (kPi / 180)}));
  EXPECT_EQ(m.channels[4], (std::vector<double>{1.5e-3, -2e-3, 0}));
  EXPECT_TRUE(m.channels[2].empty());  // omega not mapped
  EXPECT_EQ(m.ignored, (std::vector<std::string>{"counts"}));
  EXPECT_EQ(m.delimiter, ',');
}

TEST_F(MappedCsvTest, SemicolonTabQuotesCountsAndAFactorUnit) {
  const auto mapping = parse_column_mapping("Zeit [s]=t,pos=theta:counts,I=torque:*0.0551,v=omega:rpm", 8192);
  const std::string rows = "0;2048;1;60\n0.5;4096;2;-60\n1;8192;3;0\n";
  const MappedCsv semi = read_mapped_csv(file("# exported by a logger\n\"Zeit [s]\";\"pos\";I;v\n" + rows), mapping);
  EXPECT_EQ(semi.delimiter, ';');
  EXPECT_EQ(semi.channels[1], (std::vector<double>{2048 * (2 * kPi / 8192), 4096 * (2 * kPi / 8192), 2 * kPi}));
  EXPECT_EQ(semi.channels[4], (std::vector<double>{0.0551, 2 * 0.0551, 3 * 0.0551}));
  EXPECT_EQ(semi.channels[2], (std::vector<double>{2 * kPi, -2 * kPi, 0}));
  std::string tabbed = "Zeit [s]\tpos\tI\tv\n" + rows;
  for (char& c : tabbed) c = c == ';' ? '\t' : c;
  const MappedCsv tab = read_mapped_csv(file(tabbed), mapping);
  EXPECT_EQ(tab.delimiter, '\t');
  EXPECT_EQ(tab.channels, semi.channels);
  // A quoted field may hold the delimiter and a doubled quote.
  const auto quoted = read_mapped_csv(file("t,theta,torque,note\n0,0,0,\"a, \"\"b\"\"\"\n1,1,1,x\n2,2,2,y\n"),
                                      parse_column_mapping("t,theta,torque", 0));
  EXPECT_EQ(quoted.channels[0], (std::vector<double>{0, 1, 2}));
}

TEST_F(MappedCsvTest, MappingMistakesSayWhichEntryAndWhatIsAllowed) {
  const auto message = [](const std::string& text, double counts = 0) -> std::string {
    try {
      parse_column_mapping(text, counts);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message("a=t,b=angle,c=torque"),
            "--columns entry 'b=angle': unknown channel 'angle' (channels: t, theta, omega, alpha, torque, command; "
            "write SOURCE=CHANNEL[:UNIT])");
  EXPECT_EQ(message("a=t:h,b=theta,c=torque"), "--columns entry 'a=t:h': unit 'h' is not one of t's: s, ms, us, or *FACTOR");
  EXPECT_EQ(message("a=t,b=theta:counts,c=torque"),
            "--columns entry 'b=theta:counts': unit 'counts' is not one of theta's: rad, deg, rev, or *FACTOR "
            "(counts need --counts-per-rev)");
  EXPECT_EQ(message("a=t,b=theta:counts,c=torque", 4096), "");
  EXPECT_EQ(message("a=t,b=theta,c=torque:*x"), "--columns entry 'c=torque:*x': '*x': expected *FACTOR with a non-zero number");
  EXPECT_EQ(message("a=t,b=theta,b=torque"), "--columns entry 'b=torque': column 'b' mapped twice");
  EXPECT_EQ(message("a=t,b=theta,c=theta"), "--columns entry 'c=theta': channel 'theta' mapped twice");
  EXPECT_EQ(message("a=t,b=theta"), "--columns must map a column to each of t, theta and torque (missing: torque)");
}

TEST_F(MappedCsvTest, FileErrorsNameLineAndColumn) {
  const std::string head = "time_ms,angle_deg,torque_mNm\n";
  EXPECT_EQ(error_of("time,angle_deg,torque_mNm\n0,0,0\n", kMapping),
            "in.csv:1: no column 'time_ms' in the header (delimiter ','; its columns: time, angle_deg, torque_mNm)");
  EXPECT_EQ(error_of(head + "0,0,0\n1,abc,0\n", kMapping), "in.csv:3:2: column 'angle_deg': not a number: \"abc\"");
  EXPECT_EQ(error_of("time_ms;angle_deg;torque_mNm\n0;0,5;0\n", kMapping),
            "in.csv:2:2: column 'angle_deg': not a number: \"0,5\" (a decimal comma? knoblab reads '.' as the "
            "decimal point)");
  EXPECT_EQ(error_of(head + "0,0,0\n1,0\n", kMapping),
            "in.csv:3: truncated line: expected 3 fields delimited by ',' as the header, found 2");
  EXPECT_EQ(error_of(head + "0,0,0\n1,0,0,9\n", kMapping),
            "in.csv:3:4: too many fields: expected 3 fields delimited by ',' as the header, found 4");
  EXPECT_EQ(error_of(head + "0,0,0\n5,0,0\n5,0,0\n", kMapping),
            "in.csv:4:1: column 'time_ms': time not strictly increasing: 5 after 5 at line 3");
  EXPECT_EQ(error_of(head + "0,0,0\n1,,0\n", kMapping), "in.csv:3:2: column 'angle_deg': empty field");
  EXPECT_EQ(error_of(head + "0,0,0\n1,0,1e300\n2,0,0\n", "time_ms=t,angle_deg=theta,torque_mNm=torque:*1e3"),
            "in.csv:3:3: column 'torque_mNm': \"1e300\" in *1e3 is beyond ±1e12 in SI units");
  EXPECT_EQ(error_of("a,b;c\n", kMapping),
            "in.csv:1: the header holds more than one of ',', ';' and tab: say which delimits with --delimiter");
  EXPECT_EQ(error_of(head + "0,0,0\n1,1,1\n", kMapping), "in.csv:3: need at least 3 data rows, found 2");
  EXPECT_EQ(error_of(head + "0,\"1,0\n", kMapping), "in.csv:2: unterminated quote");
  EXPECT_EQ(error_of("# only comments\n", kMapping), "in.csv:1: no header line naming the columns");
}

}  // namespace
}  // namespace knoblab::interchange
