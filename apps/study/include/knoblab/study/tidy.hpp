// The pointing study's tidy table (docs/studies.md, "Analysis: the pointing
// study's report"): one row per target acquisition, three per trial in the
// thesis' Study 3, as `knoblab study export` writes it and the report reads
// it. The CSV loads unchanged in R (read.csv) and pandas (pd.read_csv):
//
//   participant,session,block,trial,practice,stage,rendering,amplitude_deg,
//   width_deg,acquisition,direction,movement_time_s,endpoint_deg,
//   overshoot_deg,rating,emg_uV,sc_uS
//
// a header line, '.' decimals, every number at full precision (the shortest
// text that reads back to the same double), an empty field for a missing
// biometric (R and pandas both read it as NA).
//
// Units: values are SI inside knoblab, but this table is an edge for people
// and statistics packages, so PointingRow keeps its columns' presentation
// units (degrees, seconds, µV, µS) as its field names say; convert at the
// point a value meets SI code.
#pragma once

#include <cstddef>
#include <istream>
#include <optional>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace knoblab::study {

struct PointingRow {
  std::string participant;   // the pseudonymous code (participant.hpp)
  unsigned session = 1;      // the participant's session, from 1
  unsigned block = 1;        // from 1, as the plan's
  unsigned trial = 1;        // the plan's trial index, from 1
  bool practice = false;     // run, not analysed (column: 0/1)
  std::string stage;         // the protocol's stage name ("all" without stages)
  std::string rendering;     // the level name of the rendering factor
  double amplitude_deg = 0;  // nominal target distance, > 0
  double width_deg = 0;      // nominal target width, > 0
  unsigned acquisition = 1;  // 1 … acquisitions, within the trial
  int direction = 1;         // the movement's sign: +1 towards positive θ, −1
  double movement_time_s = 0;  // > 0
  // Where the movement ended, from the target's centre along the movement's
  // direction: + past the centre, − short of it.
  double endpoint_deg = 0;
  // How far the knob went past the target's far edge on its way, ≥ 0.
  double overshoot_deg = 0;
  int rating = 0;  // the trial's rating (e.g. 1–9 appropriateness), on each of its rows
  std::optional<double> emg_uV;  // NA when no biometrics were recorded
  std::optional<double> sc_uS;
  bool operator==(const PointingRow&) const = default;
};

// The columns, in the order written.
const std::vector<std::string_view>& pointing_columns();

// A malformed table: what() is "line L, column C: MESSAGE" (line 1 is the
// header; the column by name, or by its 1-based position when it has none).
class TidyCsvError : public std::invalid_argument {
 public:
  TidyCsvError(std::size_t line, std::string column, const std::string& message);
  std::size_t line() const { return line_; }
  const std::string& column() const { return column_; }

 private:
  std::size_t line_;
  std::string column_;
};

// Writes the header and one line per row. Throws std::invalid_argument
// naming the row (from 0) and the column when a value cannot be written
// as the table requires: a non-finite number, an out-of-range value or
// rows of a trial that disagree (as read_pointing_csv checks), an invalid
// participant code, empty text or text with a comma, a quote or a line
// break.
void write_pointing_csv(std::ostream& out, std::span<const PointingRow> rows);

// Reads what write_pointing_csv writes, and the same table as R's
// write.csv(row.names = FALSE) or pandas write it: columns in any order,
// each once and no other; text fields optionally quoted; a whole number as
// 3 or 3.0; a missing biometric as an empty field or NA; blank lines and
// CRLF line ends. Every value is checked (numbers finite; block, trial,
// session and acquisition whole and ≥ 1; practice 0 or 1; direction ±1;
// movement time, amplitude and width > 0; overshoot ≥ 0; rating whole; the
// participant a valid pseudonymous code), and so are the rows of one trial
// (participant, session, block, trial) against each other: one rendering,
// amplitude, width, practice flag, stage and rating, each acquisition
// once. Throws TidyCsvError at the first problem: a missing, unknown or
// repeated column, a line with the wrong number of fields, a value that is
// not a number or out of range, rows of a trial that disagree.
std::vector<PointingRow> read_pointing_csv(std::istream& in);

}  // namespace knoblab::study
