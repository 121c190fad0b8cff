// The pointing tidy table as CSV (tidy.hpp). Values are checked the same way
// on the way out and on the way in, so what one writes the other reads.
#include "knoblab/study/tidy.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <format>
#include <map>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "knoblab/study/participant.hpp"

namespace knoblab::study {

namespace {

enum Column : std::size_t {
  kParticipant,
  kSession,
  kBlock,
  kTrial,
  kPractice,
  kStage,
  kRendering,
  kAmplitude,
  kWidth,
  kAcquisition,
  kDirection,
  kMovementTime,
  kEndpoint,
  kOvershoot,
  kRating,
  kEmg,
  kSc,
  kColumnCount
};

// A problem with one value: the column and what is wrong.
struct Problem {
  Column column;
  std::string message;
};

const std::string& name(Column c) {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const std::string_view n : pointing_columns()) v.emplace_back(n);
    return v;
  }();
  return names[c];
}

bool text_needs_quotes(std::string_view s) { return s.find_first_of(",\"\r\n") != std::string_view::npos; }

// The checks of one row's values on their own; the first problem, if any.
std::optional<Problem> check_values(const PointingRow& r) {
  if (!is_valid_participant_code(r.participant)) {
    try {
      check_participant_code(r.participant);
    } catch (const std::invalid_argument& e) {
      return Problem{kParticipant, e.what()};
    }
  }
  const auto text = [](Column c, const std::string& s) -> std::optional<Problem> {
    if (s.empty()) return Problem{c, "is empty"};
    if (text_needs_quotes(s)) return Problem{c, "\"" + s + "\" holds a comma, a quote or a line break"};
    return std::nullopt;
  };
  if (auto p = text(kStage, r.stage)) return p;
  if (auto p = text(kRendering, r.rendering)) return p;
  const auto from_one = [](Column c, unsigned v) -> std::optional<Problem> {
    if (v < 1) return Problem{c, "must be at least 1, got " + std::to_string(v)};
    return std::nullopt;
  };
  if (auto p = from_one(kSession, r.session)) return p;
  if (auto p = from_one(kBlock, r.block)) return p;
  if (auto p = from_one(kTrial, r.trial)) return p;
  if (auto p = from_one(kAcquisition, r.acquisition)) return p;
  if (r.direction != 1 && r.direction != -1)
    return Problem{kDirection, "must be 1 or -1, got " + std::to_string(r.direction)};
  const auto finite = [](Column c, double v) -> std::optional<Problem> {
    if (!std::isfinite(v)) return Problem{c, std::format("must be a finite number, got {}", v)};
    return std::nullopt;
  };
  const auto positive = [&](Column c, double v) -> std::optional<Problem> {
    if (auto p = finite(c, v)) return p;
    if (!(v > 0)) return Problem{c, std::format("must be > 0, got {}", v)};
    return std::nullopt;
  };
  if (auto p = positive(kAmplitude, r.amplitude_deg)) return p;
  if (auto p = positive(kWidth, r.width_deg)) return p;
  if (auto p = positive(kMovementTime, r.movement_time_s)) return p;
  if (auto p = finite(kEndpoint, r.endpoint_deg)) return p;
  if (auto p = finite(kOvershoot, r.overshoot_deg)) return p;
  if (r.overshoot_deg < 0) return Problem{kOvershoot, std::format("must be ≥ 0, got {}", r.overshoot_deg)};
  if (r.emg_uV)
    if (auto p = finite(kEmg, *r.emg_uV)) return p;
  if (r.sc_uS)
    if (auto p = finite(kSc, *r.sc_uS)) return p;
  return std::nullopt;
}

// The rows of one trial must agree on what the trial was; each acquisition
// once. Keyed by participant, session, block, trial.
class TrialChecker {
 public:
  // `where` names the row for messages ("line 7", "row 3").
  std::optional<Problem> add(const PointingRow& r, const std::string& where) {
    auto [it, fresh] = trials_.try_emplace(std::tuple(r.participant, r.session, r.block, r.trial), Seen{r, where, {}});
    Seen& s = it->second;
    if (!fresh) {
      const PointingRow& f = s.first;
      const auto differs = [&](Column c, const std::string& mine, const std::string& theirs) -> std::optional<Problem> {
        if (mine == theirs) return std::nullopt;
        return Problem{c, mine + " differs from " + theirs + " on " + s.where +
                              ", the same trial's (participant, session, block, trial)"};
      };
      if (auto p = differs(kRendering, r.rendering, f.rendering)) return p;
      if (auto p = differs(kAmplitude, std::format("{}", r.amplitude_deg), std::format("{}", f.amplitude_deg))) return p;
      if (auto p = differs(kWidth, std::format("{}", r.width_deg), std::format("{}", f.width_deg))) return p;
      if (auto p = differs(kPractice, r.practice ? "1" : "0", f.practice ? "1" : "0")) return p;
      if (auto p = differs(kStage, r.stage, f.stage)) return p;
      if (auto p = differs(kRating, std::to_string(r.rating), std::to_string(f.rating))) return p;
    }
    if (!s.acquisitions.emplace(r.acquisition, where).second)
      return Problem{kAcquisition, "acquisition " + std::to_string(r.acquisition) + " of this trial is also on " +
                                       s.acquisitions.at(r.acquisition)};
    return std::nullopt;
  }

 private:
  struct Seen {
    PointingRow first;
    std::string where;
    std::map<unsigned, std::string> acquisitions;
  };
  std::map<std::tuple<std::string, unsigned, unsigned, unsigned>, Seen> trials_;
};

std::string number(double v) { return std::format("{}", v); }

// ---- reading -------------------------------------------------------------

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// One line's fields, RFC 4180 quoting (a quoted field may hold commas and
// doubled quotes, not line breaks). Returns the position of a malformed
// field (1-based) and why, or nothing.
struct Fields {
  std::vector<std::string> values;
  std::size_t bad_field = 0;
  std::string why;
};

Fields split(std::string_view line) {
  Fields out;
  std::size_t at = 0;
  for (;;) {
    std::string field;
    if (at < line.size() && line[at] == '"') {
      ++at;
      for (;;) {
        if (at >= line.size()) {
          out.bad_field = out.values.size() + 1;
          out.why = "a quoted field is not closed on its line";
          return out;
        }
        if (line[at] == '"') {
          if (at + 1 < line.size() && line[at + 1] == '"') {
            field += '"';
            at += 2;
            continue;
          }
          ++at;
          break;
        }
        field += line[at++];
      }
      if (at < line.size() && line[at] != ',') {
        out.bad_field = out.values.size() + 1;
        out.why = "text after a quoted field's closing quote";
        return out;
      }
    } else {
      const std::size_t end = std::min(line.find(',', at), line.size());
      field = line.substr(at, end - at);
      at = end;
    }
    out.values.push_back(std::move(field));
    if (at >= line.size()) return out;
    ++at;  // the comma
  }
}

class LineReader {
 public:
  LineReader(std::size_t line, const std::vector<std::string>& fields, const std::vector<std::size_t>& position)
      : line_(line), fields_(fields), position_(position) {}

  [[noreturn]] void fail(Column c, const std::string& message) const { throw TidyCsvError(line_, name(c), message); }

  const std::string& raw(Column c) const { return fields_[position_[c]]; }

  double real(Column c) const {
    const std::string_view s = trim(raw(c));
    double v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty()) fail(c, "is empty, expected a number");
    if (ec != std::errc() || end != s.data() + s.size()) fail(c, "not a number: \"" + raw(c) + "\"");
    if (!std::isfinite(v)) fail(c, "must be a finite number, got \"" + raw(c) + "\"");
    return v;
  }

  // A whole number, written as R or pandas may write one ("3", "3.0").
  long long whole(Column c) const {
    const double v = real(c);
    if (v != std::floor(v) || std::abs(v) > 1e15) fail(c, "must be a whole number, got \"" + raw(c) + "\"");
    return static_cast<long long>(v);
  }

  unsigned from_one(Column c) const {
    const long long v = whole(c);
    if (v < 1 || v > 4294967295LL) fail(c, "must be at least 1, got " + raw(c));
    return static_cast<unsigned>(v);
  }

  std::optional<double> optional_real(Column c) const {
    const std::string_view s = trim(raw(c));
    if (s.empty() || s == "NA") return std::nullopt;
    return real(c);
  }

 private:
  std::size_t line_;
  const std::vector<std::string>& fields_;
  const std::vector<std::size_t>& position_;
};

}  // namespace

const std::vector<std::string_view>& pointing_columns() {
  static const std::vector<std::string_view> columns = {
      "participant", "session",   "block",           "trial",        "practice",      "stage",
      "rendering",   "amplitude_deg", "width_deg",   "acquisition",  "direction",     "movement_time_s",
      "endpoint_deg", "overshoot_deg", "rating",     "emg_uV",       "sc_uS"};
  return columns;
}

TidyCsvError::TidyCsvError(std::size_t line, std::string column, const std::string& message)
    : std::invalid_argument("line " + std::to_string(line) + ", column " + column + ": " + message),
      line_(line),
      column_(std::move(column)) {}

void write_pointing_csv(std::ostream& out, std::span<const PointingRow> rows) {
  TrialChecker trials;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string where = "row " + std::to_string(i);
    auto problem = check_values(rows[i]);
    if (!problem) problem = trials.add(rows[i], where);
    if (problem)
      throw std::invalid_argument("write_pointing_csv: " + where + ", column " + name(problem->column) + ": " +
                                  problem->message);
  }
  const auto& columns = pointing_columns();
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << '\n';
  const auto optional = [](const std::optional<double>& v) { return v ? number(*v) : std::string(); };
  for (const PointingRow& r : rows) {
    out << r.participant << ',' << r.session << ',' << r.block << ',' << r.trial << ',' << (r.practice ? 1 : 0) << ','
        << r.stage << ',' << r.rendering << ',' << number(r.amplitude_deg) << ',' << number(r.width_deg) << ','
        << r.acquisition << ',' << r.direction << ',' << number(r.movement_time_s) << ',' << number(r.endpoint_deg)
        << ',' << number(r.overshoot_deg) << ',' << r.rating << ',' << optional(r.emg_uV) << ',' << optional(r.sc_uS)
        << '\n';
  }
  if (!out) throw std::runtime_error("write_pointing_csv: the stream failed");
}

std::vector<PointingRow> read_pointing_csv(std::istream& in) {
  std::string line;
  std::size_t number_of_line = 0;
  // The next line that is not blank (R and pandas skip blank lines too).
  const auto next = [&]() -> bool {
    while (std::getline(in, line)) {
      ++number_of_line;
      if (number_of_line == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);  // a spreadsheet's BOM
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (!trim(line).empty()) return true;
    }
    return false;
  };
  if (!next()) throw TidyCsvError(1, "1", "the table is empty: expected a header line");

  const std::size_t header_line = number_of_line;
  const Fields header = split(line);
  if (header.bad_field) throw TidyCsvError(header_line, std::to_string(header.bad_field), header.why);
  const auto& columns = pointing_columns();
  std::vector<std::size_t> position(kColumnCount, header.values.size());
  for (std::size_t i = 0; i < header.values.size(); ++i) {
    const std::string& h = header.values[i];
    std::size_t c = 0;
    while (c < columns.size() && columns[c] != h) ++c;
    const std::string where = h.empty() ? std::to_string(i + 1) : h;
    if (c == columns.size()) {
      std::string known;
      for (const std::string_view k : columns) known += (known.empty() ? "" : ", ") + std::string(k);
      throw TidyCsvError(header_line, where,
                         "unknown column" + std::string(h.empty() ? " (unnamed: R's row names? write.csv with "
                                                                    "row.names = FALSE)"
                                                                  : "") +
                             "; the table's columns are " + known);
    }
    if (position[c] != header.values.size()) throw TidyCsvError(header_line, where, "the column is named twice");
    position[c] = i;
  }
  for (std::size_t c = 0; c < kColumnCount; ++c)
    if (position[c] == header.values.size())
      throw TidyCsvError(header_line, name(static_cast<Column>(c)), "missing column");

  std::vector<PointingRow> rows;
  TrialChecker trials;
  while (next()) {
    const Fields f = split(line);
    if (f.bad_field) {
      const std::string where =
          f.bad_field <= header.values.size() ? header.values[f.bad_field - 1] : std::to_string(f.bad_field);
      throw TidyCsvError(number_of_line, where, f.why);
    }
    if (f.values.size() != header.values.size()) {
      const std::string where = f.values.size() < header.values.size() ? header.values[f.values.size()]
                                                                         : std::to_string(f.values.size());
      throw TidyCsvError(number_of_line, where,
                         "expected " + std::to_string(header.values.size()) + " fields as the header has, got " +
                             std::to_string(f.values.size()));
    }
    const LineReader v(number_of_line, f.values, position);
    PointingRow r;
    r.participant = v.raw(kParticipant);
    r.session = v.from_one(kSession);
    r.block = v.from_one(kBlock);
    r.trial = v.from_one(kTrial);
    const long long practice = v.whole(kPractice);
    if (practice != 0 && practice != 1) v.fail(kPractice, "must be 0 or 1, got " + v.raw(kPractice));
    r.practice = practice == 1;
    r.stage = v.raw(kStage);
    r.rendering = v.raw(kRendering);
    r.amplitude_deg = v.real(kAmplitude);
    r.width_deg = v.real(kWidth);
    r.acquisition = v.from_one(kAcquisition);
    const long long direction = v.whole(kDirection);
    if (direction != 1 && direction != -1) v.fail(kDirection, "must be 1 or -1, got " + v.raw(kDirection));
    r.direction = static_cast<int>(direction);
    r.movement_time_s = v.real(kMovementTime);
    r.endpoint_deg = v.real(kEndpoint);
    r.overshoot_deg = v.real(kOvershoot);
    const long long rating = v.whole(kRating);
    if (rating < -1000000 || rating > 1000000) v.fail(kRating, "out of range: " + v.raw(kRating));
    r.rating = static_cast<int>(rating);
    r.emg_uV = v.optional_real(kEmg);
    r.sc_uS = v.optional_real(kSc);
    auto problem = check_values(r);
    if (!problem) problem = trials.add(r, "line " + std::to_string(number_of_line));
    if (problem) v.fail(problem->column, problem->message);
    rows.push_back(std::move(r));
  }
  if (in.bad()) throw std::runtime_error("read_pointing_csv: reading failed after line " + std::to_string(number_of_line));
  return rows;
}

}  // namespace knoblab::study
