// CSV reading: header → column map, rows → channels, then derive what is
// missing. Every rejection is a CsvError with line and field numbers.
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "knoblab/interchange/utf8.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/model/filters.hpp"
#include "csv_fields.hpp"
#include "line_reader.hpp"

namespace knoblab::interchange {

CsvError::CsvError(std::string source, std::size_t line, std::size_t column, std::string reason)
    : std::runtime_error([&] {
        std::string m = source;
        if (line > 0) m += ":" + std::to_string(line);
        if (line > 0 && column > 0) m += ":" + std::to_string(column);
        return m + ": " + reason;
      }()),
      source_(std::move(source)),
      line_(line),
      column_(column),
      reason_(std::move(reason)) {}

namespace {

using detail::NumError;
using detail::parse_number;
using detail::quote;
using detail::trim;

enum Channel : std::size_t { kT, kTheta, kOmega, kAlpha, kTorque, kCommand, kChannelCount };
// The flags column's index in the column map: after the channels.
constexpr std::size_t kFlags = kChannelCount;

std::string_view column_name(std::size_t ch) { return ch == kFlags ? kFlagsColumn : kChannelNames[ch]; }

void split(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  for (;;) {
    const auto comma = line.find(',');
    fields.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return;
    line.remove_prefix(comma + 1);
  }
}

std::string allowed_list() {
  std::string s;
  for (auto name : kChannelNames) s += (s.empty() ? "" : ", ") + std::string(name);
  return s + ", " + std::string(kFlagsColumn);
}

// A flags field: an unsigned decimal integer that fits SampleFlag's 32 bits.
NumError parse_flags(std::string_view f, std::uint32_t& out) {
  if (f.empty()) return NumError::kEmpty;
  if (f.front() < '0' || f.front() > '9') return NumError::kNotUnsigned;  // no sign, no space
  const char* end = f.data() + f.size();
  const auto [ptr, ec] = std::from_chars(f.data(), end, out);
  if (ec == std::errc::result_out_of_range) return NumError::kOutOfRange;
  if (ec != std::errc() || ptr != end) return NumError::kNotUnsigned;
  return NumError::kNone;
}

// ';' or a tab inside a trimmed field means the file uses another delimiter.
std::optional<char> foreign_delimiter(const std::vector<std::string_view>& fields) {
  for (auto f : fields)
    for (char c : f)
      if (c == ';' || c == '\t') return c;
  return std::nullopt;
}

std::string delimiter_message(char c) {
  return std::string("expected ',' delimiter, found ") + (c == '\t' ? "'\\t' (tab)" : "';'");
}

class Parser {
 public:
  Parser(std::istream& in, std::string source) : source_(std::move(source)), lines_(in, source_) {}

  Recording run() {
    read_preamble();
    read_rows();
    finish();
    if (map_line_ == 0) return std::move(cap_);
    return StaticMap{std::move(cap_.metadata), std::move(cap_.theta), std::move(cap_.torque)};
  }

  // The line of `# kind: static-map`; 0 for a recording over time.
  std::size_t map_line() const { return map_line_; }

 private:
  [[noreturn]] void fail(std::size_t line, std::size_t column, std::string reason) const {
    throw CsvError(source_, line, column, std::move(reason));
  }
  std::size_t line_no() const { return lines_.line_number(); }

  // Metadata comments (and blank lines) up to and including the header.
  void read_preamble() {
    std::size_t budget = 0;
    for (bool first = true;; first = false) {
      if (!lines_.next(line_)) {
        if (line_no() == 0)
          fail(1, 0, "empty file: expected a header line such as 't,theta,torque'");
        fail(line_no(), 0, "no header line after the metadata comments");
      }
      std::string_view sv = line_;
      if (first && sv.starts_with("\xEF\xBB\xBF")) sv.remove_prefix(3);  // UTF-8 BOM
      budget += line_.size() + 1;
      if (budget > kMaxMetadataBytes)
        fail(line_no(), 0, "no header line within the first " +
                               std::to_string(kMaxMetadataBytes) + " bytes");
      sv = trim(sv);
      if (sv.empty()) continue;
      if (sv.front() == '#') {
        add_metadata(sv.substr(1));
        continue;
      }
      parse_header(sv);
      return;
    }
  }

  void add_metadata(std::string_view body) {
    // Metadata reaches the store as JSON text, which must be UTF-8.
    if (const auto bad = first_invalid_utf8(body))
      fail(line_no(), 0, "metadata is not valid UTF-8 (byte " + std::to_string(*bad + 2) +
                             " of the line); save the file as UTF-8");
    body = trim(body);
    const auto colon = body.find(':');
    if (colon == std::string_view::npos) {
      cap_.metadata.emplace_back("", std::string(body));  // free comment
      return;
    }
    const std::string_view key = trim(body.substr(0, colon)), value = trim(body.substr(colon + 1));
    if (key != kKindKey) {
      cap_.metadata.emplace_back(std::string(key), std::string(value));
      return;
    }
    // The kind says how to read the rest, so it is not kept as metadata.
    if (kind_line_ != 0) fail(line_no(), 0, "a second kind line (the first is line " + std::to_string(kind_line_) + ")");
    kind_line_ = line_no();
    if (value == kStaticMapKind) map_line_ = line_no();
    else if (value != "time-series")
      fail(line_no(), 0, "unknown kind " + quote(value) + " (time-series, the default, or static-map)");
  }

  void parse_header(std::string_view header) {
    header_line_ = line_no();
    split(header, fields_);
    if (auto c = foreign_delimiter(fields_)) fail(header_line_, 0, delimiter_message(*c));
    std::array<std::size_t, kChannelCount + 1> seen{};  // column (1-based) per channel/flags, 0 = absent
    for (std::size_t i = 0; i < fields_.size(); ++i) {
      const auto name = fields_[i];
      const std::size_t col = i + 1;
      if (name.empty()) fail(header_line_, col, "empty column name");
      std::size_t ch = 0;
      while (ch < kChannelCount && kChannelNames[ch] != name) ++ch;
      if (ch == kChannelCount && name == kFlagsColumn) ch = kFlags;
      else if (ch == kChannelCount) {
        double ignored;
        if (parse_number(name, ignored) == NumError::kNone)
          fail(header_line_, col, "expected a header line naming the columns (" + allowed_list() +
                                      "), found the number " + quote(name));
        fail(header_line_, col,
             "unknown column " + quote(name) + " (allowed: " + allowed_list() + ")");
      }
      if (seen[ch] != 0)
        fail(header_line_, col, "duplicate column '" + std::string(name) + "' (also column " +
                                    std::to_string(seen[ch]) + ")");
      if (map_line_ != 0 && ch != kTheta && ch != kTorque)
        fail(header_line_, col, "column '" + std::string(name) + "' in a static map (kind line " +
                                    std::to_string(map_line_) + "): a map holds only theta and torque, no time");
      seen[ch] = col;
      columns_.push_back(ch);
    }
    std::string missing;
    std::size_t n_missing = 0;
    const auto required = map_line_ != 0 ? std::vector<std::size_t>{kTheta, kTorque}
                                         : std::vector<std::size_t>{kT, kTheta, kTorque};
    for (std::size_t ch : required)
      if (seen[ch] == 0) {
        missing += (missing.empty() ? "'" : ", '") + std::string(kChannelNames[ch]) + "'";
        ++n_missing;
      }
    if (n_missing > 0)
      fail(header_line_, 0, std::string(n_missing == 1 ? "missing required column "
                                                       : "missing required columns ") +
                                missing + (map_line_ != 0 ? " (a static map holds theta and torque)"
                                                          : " (t, theta and torque are required)"));
    cap_.has_command = seen[kCommand] != 0;
    cap_.omega_derived = seen[kOmega] == 0;
    cap_.alpha_derived = seen[kAlpha] == 0;
    t_col_ = seen[map_line_ != 0 ? kTheta : kT];
  }

  std::vector<double>& channel(std::size_t ch) {
    switch (ch) {
      case kT: return cap_.t;
      case kTheta: return cap_.theta;
      case kOmega: return cap_.omega;
      case kAlpha: return cap_.alpha;
      case kTorque: return cap_.torque;
      default: return cap_.command;
    }
  }

  void read_rows() {
    std::vector<std::vector<double>*> dest;  // nullptr: the flags column
    for (std::size_t ch : columns_) dest.push_back(ch == kFlags ? nullptr : &channel(ch));
    const std::size_t n = columns_.size();
    std::size_t blank_line = 0, blanks = 0, prev_t_line = 0;
    double prev_t = 0;
    while (lines_.next(line_)) {
      const std::string_view sv = trim(line_);
      if (sv.empty()) {
        // Trailing empty lines are fine; a long run of them is garbage.
        if (blank_line == 0) blank_line = line_no();
        if (++blanks > 64) fail(line_no(), 0, "too many empty lines");
        continue;
      }
      if (blank_line != 0) fail(blank_line, 0, "empty line inside the data");
      if (sv.front() == '#') fail(line_no(), 0, "comment lines must come before the header");
      split(sv, fields_);
      if (fields_.size() != n) {
        if (auto c = foreign_delimiter(fields_)) fail(line_no(), 0, delimiter_message(*c));
        if (fields_.size() < n)
          fail(line_no(), 0, "truncated line: expected " + std::to_string(n) + " fields, found " +
                                 std::to_string(fields_.size()));
        fail(line_no(), n + 1, "too many fields: expected " + std::to_string(n) + ", found " +
                                   std::to_string(fields_.size()));
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (!dest[i]) {
          std::uint32_t f = 0;
          const NumError e = parse_flags(fields_[i], f);
          if (e != NumError::kNone) field_error(e, i);
          cap_.flags.push_back(f);
          continue;
        }
        double v = 0;
        const NumError e = parse_number(fields_[i], v);
        if (e != NumError::kNone) field_error(e, i);
        if (std::abs(v) > kMaxMagnitude)
          fail(line_no(), i + 1, "column '" + std::string(column_name(columns_[i])) + "': " + quote(fields_[i]) +
                                     " is beyond ±1e12: no measurement in SI units is that large "
                                     "(a corrupted file, or a value in the wrong unit?)");
        dest[i]->push_back(v);
      }
      if (first_row_line_ == 0) first_row_line_ = line_no();
      // Time orders a recording; position orders a static map.
      const double t = map_line_ != 0 ? cap_.theta.back() : cap_.t.back();
      if (prev_t_line != 0 && !(t > prev_t))
        fail(line_no(), t_col_, std::string(map_line_ != 0 ? "column 'theta': positions" : "column 't': time") +
                                    " not strictly increasing: " +
                                    std::string(fields_[t_col_ - 1]) + " at line " +
                                    std::to_string(line_no()) + " after " + format(prev_t) +
                                    " at line " + std::to_string(prev_t_line));
      prev_t = t;
      prev_t_line = line_no();
    }
  }

  [[noreturn]] void field_error(NumError e, std::size_t i) const {
    const std::string prefix = "column '" + std::string(column_name(columns_[i])) + "': ";
    const auto f = fields_[i];
    switch (e) {
      case NumError::kEmpty: fail(line_no(), i + 1, prefix + "empty field");
      case NumError::kNotFinite: fail(line_no(), i + 1, prefix + "not finite: " + quote(f));
      case NumError::kOutOfRange:
        if (columns_[i] == kFlags)
          fail(line_no(), i + 1, prefix + "more than 32 bits: " + quote(f));
        fail(line_no(), i + 1, prefix + "out of double range: " + quote(f));
      case NumError::kNotUnsigned:
        if (auto c = foreign_delimiter(fields_)) fail(line_no(), 0, delimiter_message(*c));
        fail(line_no(), i + 1, prefix + "not an unsigned integer (SampleFlag bits): " + quote(f));
      default:
        if (auto c = foreign_delimiter(fields_)) fail(line_no(), 0, delimiter_message(*c));
        fail(line_no(), i + 1, prefix + "not a number: " + quote(f));
    }
  }

  static std::string format(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
  }

  void finish() {
    const std::size_t rows = cap_.theta.size();
    if (rows < kMinRows)
      fail(line_no(), 0, "need at least " + std::to_string(kMinRows) + " data rows, found " +
                             std::to_string(rows));
    if (map_line_ != 0) {
      if (!(cap_.theta.back() - cap_.theta.front() < 2 * std::numbers::pi))
        fail(first_row_line_ + rows - 1, t_col_, "column 'theta': a static map holds one revolution, these "
                                                 "positions span " + format(cap_.theta.back() - cap_.theta.front()) +
                                                 " rad (2*pi or more)");
      return;
    }
    if (cap_.omega_derived) {
      cap_.omega = model::derivative(cap_.t, cap_.theta);
      check_derived(cap_.omega, "omega", "theta");
    }
    if (cap_.alpha_derived) {
      cap_.alpha = model::derivative(cap_.t, cap_.omega);
      check_derived(cap_.alpha, "alpha", cap_.omega_derived ? "theta" : "omega");
    }
  }

  // A derived channel is the file's own data differenced over its time
  // steps: rows too close in time for their change overflow it. Named by the
  // line of the row, like any other error in the file.
  void check_derived(const std::vector<double>& v, const char* name, const char* from) const {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]) || std::abs(v[i]) > kMaxMagnitude)
        fail(first_row_line_ + i, 0, std::string(name) + " (not in the file, derived from " + from +
                                         " and t) is beyond ±1e12 here: the rows around this line are too "
                                         "close in time for their change in " + from);
  }

  std::string source_;
  detail::LineReader lines_;
  Capture cap_;
  std::string line_;
  std::vector<std::string_view> fields_;
  std::vector<std::size_t> columns_;  // channel of each field
  std::size_t header_line_ = 0, t_col_ = 0;  // t_col_: theta's in a static map
  std::size_t kind_line_ = 0, map_line_ = 0;
  std::size_t first_row_line_ = 0;  // data rows are consecutive lines from here
};

}  // namespace

Recording parse_recording(std::istream& in, std::string_view source_name) {
  return Parser(in, std::string(source_name)).run();
}

Capture parse_csv(std::istream& in, std::string_view source_name) {
  Parser parser(in, std::string(source_name));
  Recording r = parser.run();
  if (auto* c = std::get_if<Capture>(&r)) return std::move(*c);
  throw CsvError(std::string(source_name), parser.map_line(), 0,
                 "a static map (torque over position, no time stamps), not a recording over time: "
                 "'knoblab inspect' reads it; fit, import and discrepancy need a recording over time "
                 "(to fit a knob's detents, record it turning slowly instead)");
}

namespace {
std::ifstream open_csv(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw CsvError(path.string(), 0, 0, "is a directory, not a CSV file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CsvError(path.string(), 0, 0, std::string("cannot open: ") + std::strerror(errno));
  return in;
}
}  // namespace

Capture read_csv(const std::filesystem::path& path) {
  std::ifstream in = open_csv(path);
  return parse_csv(in, path.string());
}

Recording read_recording(const std::filesystem::path& path) {
  std::ifstream in = open_csv(path);
  return parse_recording(in, path.string());
}

}  // namespace knoblab::interchange
