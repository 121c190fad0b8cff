// The pointing tidy table as CSV: what is written reads back identically, in
// the column order the table promises, and a malformed table is refused
// naming its line and column.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "knoblab/study/tidy.hpp"
#include "pointing_data.hpp"

namespace knoblab::study {
namespace {

const char* const kHeader =
    "participant,session,block,trial,practice,stage,rendering,amplitude_deg,width_deg,acquisition,direction,"
    "movement_time_s,endpoint_deg,overshoot_deg,rating,emg_uV,sc_uS";

std::string csv(const std::vector<PointingRow>& rows) {
  std::ostringstream out;
  write_pointing_csv(out, rows);
  return out.str();
}

std::vector<PointingRow> read(const std::string& text) {
  std::istringstream in(text);
  return read_pointing_csv(in);
}

PointingRow row() {
  PointingRow r;
  r.participant = "P01";
  r.stage = "all";
  r.rendering = "low-friction";
  r.amplitude_deg = 30;
  r.width_deg = 1.4;
  r.movement_time_s = 0.1 + 0.2;  // 0.30000000000000004: only full precision reads back
  r.endpoint_deg = -0.123456789012345678;
  r.overshoot_deg = 0;
  r.rating = 7;
  r.emg_uV = 3.25e-7;
  return r;
}

// The line of `text` whose number is `line`, with one field replaced.
std::string with_field(std::string text, std::size_t line, std::size_t field, const std::string& value) {
  std::size_t at = 0;
  for (std::size_t l = 1; l < line; ++l) at = text.find('\n', at) + 1;
  for (std::size_t f = 0; f < field; ++f) at = text.find(',', at) + 1;
  const std::size_t end = text.find_first_of(",\n", at);
  return text.replace(at, end - at, value);
}

void expect_refused(const std::string& text, std::size_t line, const std::string& column, const std::string& says) {
  try {
    read(text);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const TidyCsvError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.column(), column) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    EXPECT_TRUE(std::string(e.what()).starts_with("line " + std::to_string(line) + ", column " + column + ": "))
        << e.what();
  }
}

TEST(TidyCsv, WritesTheHeaderThenOneLinePerAcquisitionInTheColumnOrder) {
  PointingRow r = row();
  r.practice = true;
  r.direction = -1;
  r.sc_uS = std::nullopt;
  const std::string text = csv({r});
  EXPECT_EQ(text, std::string(kHeader) +
                      "\nP01,1,1,1,1,all,low-friction,30,1.4,1,-1,0.30000000000000004,-0.12345678901234568,0,7,"
                      "3.25e-07,\n");
  std::string joined;
  for (const auto c : pointing_columns()) joined += (joined.empty() ? "" : ",") + std::string(c);
  EXPECT_EQ(joined, kHeader);
}

TEST(TidyCsv, ASyntheticStudyReadsBackExactly) {
  const auto rows = test::synthetic_pointing({.participants = 4, .analysed_blocks = 1, .incomplete_participant = true});
  ASSERT_GT(rows.size(), 600u);
  const auto back = read(csv(rows));
  ASSERT_EQ(back.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) ASSERT_EQ(back[i], rows[i]) << "row " << i;
  std::size_t missing = 0;
  for (const auto& r : back) missing += r.emg_uV ? 0 : 1;
  EXPECT_GT(missing, 0u);  // the NAs came back as NA
}

TEST(TidyCsv, ReadsTheTableAsRWritesItQuotedReorderedWithNA) {
  // R's write.csv(d, row.names = FALSE): text quoted, NA for missing; CRLF
  // line ends, a blank line and the columns in another order are accepted.
  const std::string text =
      "\"rendering\",\"participant\",\"session\",\"block\",\"trial\",\"practice\",\"stage\",\"amplitude_deg\","
      "\"width_deg\",\"acquisition\",\"direction\",\"movement_time_s\",\"endpoint_deg\",\"overshoot_deg\","
      "\"rating\",\"emg_uV\",\"sc_uS\"\r\n"
      "\"low-friction\",\"P01\",1,1,1,0,\"all\",30,1.4,1,1,0.5,0.25,0,7,NA,1.5\r\n"
      "\r\n"
      "\"low-friction\",\"P01\",1,1,1,0,\"all\",30,1.4,2,-1,0.5,-0.25,1.0,7,2,NA\r\n";
  const auto rows = read(text);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].rendering, "low-friction");
  EXPECT_FALSE(rows[0].emg_uV);
  EXPECT_EQ(rows[0].sc_uS, 1.5);
  EXPECT_EQ(rows[1].emg_uV, 2.0);
  EXPECT_FALSE(rows[1].sc_uS);
  EXPECT_EQ(rows[1].overshoot_deg, 1.0);
}

TEST(TidyCsv, AMissingColumnIsRefusedByName) {
  std::string text = csv({row()});
  text.replace(text.find(",sc_uS"), 6, "");
  expect_refused(text, 1, "sc_uS", "missing column");
}

TEST(TidyCsv, AnUnknownOrRepeatedColumnIsRefused) {
  expect_refused(std::string("\"\",") + kHeader + "\n", 1, "1", "row.names = FALSE");
  expect_refused(std::string(kHeader) + ",notes\n", 1, "notes", "unknown column");
  expect_refused(std::string(kHeader) + ",rating\n", 1, "rating", "named twice");
}

TEST(TidyCsv, ANonNumberIsRefusedNamingLineAndColumn) {
  const std::string text = csv({row(), [] {
                                  PointingRow r = row();
                                  r.acquisition = 2;
                                  return r;
                                }()});
  expect_refused(with_field(text, 3, 11, "fast"), 3, "movement_time_s", "not a number: \"fast\"");
  expect_refused(with_field(text, 2, 12, ""), 2, "endpoint_deg", "is empty");
  expect_refused(with_field(text, 2, 7, "inf"), 2, "amplitude_deg", "finite");
  expect_refused(with_field(text, 2, 7, "3,0"), 2, "18", "expected 17 fields as the header has, got 18");  // a decimal comma
  expect_refused(with_field(text, 3, 14, "6.5"), 3, "rating", "whole number");
}

TEST(TidyCsv, AWrongFieldCountIsRefusedNamingTheFirstMissingColumn) {
  std::string text = csv({row()});
  text.erase(text.rfind(','));  // the last field and its comma
  text += "\n";
  expect_refused(text, 2, "sc_uS", "expected 17 fields as the header has, got 16");
}

TEST(TidyCsv, ValuesOutOfRangeAreRefused) {
  const std::string text = csv({row()});
  expect_refused(with_field(text, 2, 4, "2"), 2, "practice", "0 or 1");
  expect_refused(with_field(text, 2, 10, "0"), 2, "direction", "1 or -1");
  expect_refused(with_field(text, 2, 11, "0"), 2, "movement_time_s", "> 0");
  expect_refused(with_field(text, 2, 13, "-0.5"), 2, "overshoot_deg", "≥ 0");
  expect_refused(with_field(text, 2, 2, "0"), 2, "block", "at least 1");
  expect_refused(with_field(text, 2, 0, "Alice"), 2, "participant", "never a name");
  expect_refused(with_field(text, 2, 6, ""), 2, "rendering", "is empty");
  expect_refused(std::string("\"participant\n"), 1, "1", "not closed");
}

TEST(TidyCsv, RowsOfOneTrialMustAgree) {
  PointingRow second = row();
  second.acquisition = 2;
  second.rating = 3;
  expect_refused(csv({row()}) + csv({second}).substr(std::string(kHeader).size() + 1), 3, "rating",
                 "differs from 7 on line 2");
  second.rating = 7;
  second.acquisition = 1;
  expect_refused(csv({row()}) + csv({second}).substr(std::string(kHeader).size() + 1), 3, "acquisition",
                 "also on line 2");
}

TEST(TidyCsv, AnEmptyTableIsRefused) {
  expect_refused("", 1, "1", "empty");
  EXPECT_TRUE(read(std::string(kHeader) + "\n").empty());
}

TEST(TidyCsv, WritingRefusesWhatCouldNotBeReadBack) {
  std::ostringstream out;
  PointingRow r = row();
  r.rendering = "a,b";
  EXPECT_THROW(write_pointing_csv(out, std::vector{r}), std::invalid_argument);
  r = row();
  r.movement_time_s = std::nan("");
  try {
    write_pointing_csv(out, std::vector{r});
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 0, column movement_time_s"), std::string::npos) << e.what();
  }
  r = row();
  PointingRow twin = r;
  twin.rendering = "high-friction";
  twin.acquisition = 2;
  EXPECT_THROW(write_pointing_csv(out, std::vector{r, twin}), std::invalid_argument);
  EXPECT_TRUE(out.str().empty());  // nothing written before the check
}

}  // namespace
}  // namespace knoblab::study
