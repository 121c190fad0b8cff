// Other tools' CSV through a column mapping (mapped_csv.hpp). The interchange
// reader's line reader and field parsing are reused; what differs is the
// header (the file's own names), the delimiter and quoting, and units.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "csv_fields.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/mapped_csv.hpp"
#include "line_reader.hpp"

namespace knoblab::interchange {

namespace {

using detail::NumError;
using detail::parse_number;
using detail::quote;
using detail::trim;

enum Channel : std::size_t { kT, kTheta, kOmega, kAlpha, kTorque, kCommand };
constexpr double kTwoPi = 2 * std::numbers::pi;

std::string units_list(const std::vector<Unit>& units) {
  std::string s;
  for (const auto& u : units) s += (s.empty() ? "" : ", ") + u.name;
  return s + ", or *FACTOR";
}

std::string delimiter_name(char d) { return d == '\t' ? "tab" : std::string("'") + d + "'"; }

// Splits one line at `delim`, honouring double quotes; false for an
// unterminated quote. Unquoted fields are trimmed of spaces and tabs.
bool split(std::string_view line, char delim, std::vector<std::string>& fields) {
  fields.clear();
  std::string field;
  bool quoted = false, was_quoted = false;
  const auto finish = [&] {
    fields.push_back(was_quoted ? field : std::string(trim(field)));
    field.clear();
    was_quoted = false;
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"' && trim(field).empty()) {
      quoted = was_quoted = true;
      field.clear();
    } else if (c == delim) {
      finish();
    } else if (!was_quoted || (c != ' ' && c != '\t')) {
      field += c;
    }
  }
  finish();
  return !quoted;
}

// A CsvError at the line just read.
struct Fail {
  const std::string& source;
  const detail::LineReader& lines;
  [[noreturn]] void operator()(std::size_t column, const std::string& reason) const {
    throw CsvError(source, lines.line_number(), column, reason);
  }
};

}  // namespace

std::vector<Unit> channel_units(std::size_t channel, double counts_per_rev) {
  const double deg = std::numbers::pi / 180;
  std::vector<Unit> u;
  const auto add_counts = [&](const char* name, double per_rev) {
    if (counts_per_rev > 0) u.push_back({name, kTwoPi / counts_per_rev, per_rev});
  };
  switch (channel) {
    case kT: u = {{"s", 1}, {"ms", 1e-3}, {"us", 1e-6}}; break;
    case kTheta:
      u = {{"rad", 1, kTwoPi}, {"deg", deg, 360}, {"rev", kTwoPi, 1}};
      add_counts("counts", counts_per_rev);
      break;
    case kOmega:
      u = {{"rad/s", 1}, {"deg/s", deg}, {"rev/s", kTwoPi}, {"rpm", kTwoPi / 60}};
      add_counts("counts/s", 0);
      break;
    case kAlpha:
      u = {{"rad/s^2", 1}, {"deg/s^2", deg}, {"rev/s^2", kTwoPi}};
      add_counts("counts/s^2", 0);
      break;
    case kTorque: u = {{"N*m", 1}, {"mN*m", 1e-3}, {"uN*m", 1e-6}}; break;
    case kCommand: u = {{"V", 1}, {"mV", 1e-3}}; break;
    default: throw std::out_of_range("channel_units: no channel " + std::to_string(channel));
  }
  return u;
}

std::vector<ColumnMapping> parse_column_mapping(std::string_view text, double counts_per_rev) {
  std::vector<ColumnMapping> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string_view entry = trim(text.substr(start, comma == std::string_view::npos ? comma : comma - start));
    const std::string where = "--columns entry '" + std::string(entry) + "'";
    const std::size_t eq = entry.find('=');
    const std::string_view target = eq == std::string_view::npos ? entry : entry.substr(eq + 1);
    const std::size_t colon = target.find(':');
    const std::string channel(trim(target.substr(0, colon)));
    const auto it = std::find(kChannelNames.begin(), kChannelNames.end(), channel);
    if (it == kChannelNames.end())
      throw std::invalid_argument(where + ": unknown channel '" + channel +
                                  "' (channels: t, theta, omega, alpha, torque, command; "
                                  "write SOURCE=CHANNEL[:UNIT])");
    ColumnMapping m;
    m.channel = static_cast<std::size_t>(it - kChannelNames.begin());
    m.source = eq == std::string_view::npos ? channel : std::string(trim(entry.substr(0, eq)));
    if (m.source.empty()) throw std::invalid_argument(where + ": no source column before '='");
    const auto units = channel_units(m.channel, counts_per_rev);
    m.unit = units.front();  // SI
    if (colon != std::string_view::npos) {
      const std::string unit(trim(target.substr(colon + 1)));
      if (unit.starts_with('*')) {
        double factor = 0;
        if (parse_number(unit.substr(1), factor) != NumError::kNone || factor == 0)
          throw std::invalid_argument(where + ": '" + unit + "': expected *FACTOR with a non-zero number");
        m.unit = {unit, factor, m.channel == kTheta ? kTwoPi / std::abs(factor) : 0.0};
      } else {
        const auto u = std::find_if(units.begin(), units.end(), [&](const Unit& x) { return x.name == unit; });
        if (u == units.end())
          throw std::invalid_argument(
              where + ": unit '" + unit + "' is not one of " + channel + "'s: " + units_list(units) +
              (unit.starts_with("counts") && counts_per_rev <= 0 ? " (counts need --counts-per-rev)" : ""));
        m.unit = *u;
      }
    }
    for (const auto& prev : out) {
      if (prev.channel == m.channel) throw std::invalid_argument(where + ": channel '" + channel + "' mapped twice");
      if (prev.source == m.source) throw std::invalid_argument(where + ": column '" + m.source + "' mapped twice");
    }
    out.push_back(std::move(m));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  for (std::size_t ch : {kT, kTheta, kTorque})
    if (std::none_of(out.begin(), out.end(), [&](const ColumnMapping& m) { return m.channel == ch; }))
      throw std::invalid_argument("--columns must map a column to each of t, theta and torque (missing: " +
                                  std::string(kChannelNames[ch]) + ")");
  return out;
}

std::string mapping_text(const std::vector<ColumnMapping>& mapping) {
  std::string s;
  for (const auto& m : mapping)
    s += (s.empty() ? "" : ",") + m.source + "=" + std::string(kChannelNames[m.channel]) + ":" + m.unit.name;
  return s;
}

MappedCsv read_mapped_csv(const std::filesystem::path& path, const std::vector<ColumnMapping>& mapping,
                          char delimiter) {
  const std::string source = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw CsvError(source, 0, 0, "is a directory, not a CSV file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CsvError(source, 0, 0, std::string("cannot open: ") + std::strerror(errno));
  detail::LineReader lines(in, source);
  const Fail fail{source, lines};

  // The header: the first line that is neither empty nor a '#' comment.
  std::string line;
  std::string_view header;
  while (lines.next(line)) {
    header = trim(line);
    if (lines.line_number() == 1 && header.starts_with("\xEF\xBB\xBF")) header = trim(header.substr(3));
    if (!header.empty() && header.front() != '#') break;
    header = {};
  }
  if (header.empty()) throw CsvError(source, lines.line_number(), 0, "no header line naming the columns");
  MappedCsv out;
  if (delimiter == 0) {
    std::string found;
    for (char d : {',', ';', '\t'})
      if (header.find(d) != std::string_view::npos) found += d;
    if (found.size() > 1)
      fail(0, "the header holds more than one of ',', ';' and tab: say which delimits with --delimiter");
    delimiter = found.empty() ? ',' : found[0];
  }
  out.delimiter = delimiter;
  std::vector<std::string> names;
  if (!split(header, delimiter, names)) fail(0, "unterminated quote in the header");

  // Column index of each mapping entry; every other column is ignored.
  std::vector<std::size_t> column_of(mapping.size());
  for (std::size_t k = 0; k < mapping.size(); ++k) {
    const auto first = std::find(names.begin(), names.end(), mapping[k].source);
    if (first == names.end()) {
      std::string all;
      for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
      fail(0, "no column '" + mapping[k].source + "' in the header (delimiter " + delimiter_name(delimiter) +
                  "; its columns: " + all + ")");
    }
    if (std::find(first + 1, names.end(), mapping[k].source) != names.end())
      fail(static_cast<std::size_t>(first - names.begin()) + 1,
           "column '" + mapping[k].source + "' appears twice in the header");
    column_of[k] = static_cast<std::size_t>(first - names.begin());
  }
  for (const auto& n : names)
    if (std::none_of(mapping.begin(), mapping.end(), [&](const ColumnMapping& m) { return m.source == n; }))
      out.ignored.push_back(n);

  std::vector<std::string> fields;
  const std::size_t t_index = static_cast<std::size_t>(
      std::find_if(mapping.begin(), mapping.end(), [](const ColumnMapping& m) { return m.channel == kT; }) -
      mapping.begin());
  std::size_t blank_line = 0, prev_t_line = 0;
  std::string prev_t_text;
  while (lines.next(line)) {
    const std::string_view sv = trim(line);
    if (sv.empty()) {
      if (blank_line == 0) blank_line = lines.line_number();
      continue;
    }
    if (blank_line != 0) throw CsvError(source, blank_line, 0, "empty line inside the data");
    if (!split(sv, delimiter, fields)) fail(0, "unterminated quote");
    if (fields.size() != names.size())
      fail(fields.size() < names.size() ? 0 : names.size() + 1,
           std::string(fields.size() < names.size() ? "truncated line" : "too many fields") + ": expected " +
               std::to_string(names.size()) + " fields delimited by " + delimiter_name(delimiter) + " as the header, found " +
               std::to_string(fields.size()));
    for (std::size_t k = 0; k < mapping.size(); ++k) {
      const std::size_t col = column_of[k];
      const std::string& f = fields[col];
      const std::string prefix = "column '" + mapping[k].source + "': ";
      double v = 0;
      switch (parse_number(f, v)) {
        case NumError::kNone: break;
        case NumError::kEmpty: fail(col + 1, prefix + "empty field");
        case NumError::kNotFinite: fail(col + 1, prefix + "not finite: " + quote(f));
        case NumError::kOutOfRange: fail(col + 1, prefix + "out of double range: " + quote(f));
        default:
          fail(col + 1, prefix + "not a number: " + quote(f) +
                            (f.find(',') != std::string::npos ? " (a decimal comma? knoblab reads '.' as the decimal point)" : ""));
      }
      v *= mapping[k].unit.scale;
      if (!std::isfinite(v) || std::abs(v) > kMaxMagnitude)
        fail(col + 1, prefix + quote(f) + " in " + mapping[k].unit.name + " is beyond ±1e12 in SI units");
      out.channels[mapping[k].channel].push_back(v);
    }
    const auto& t = out.channels[kT];
    const std::string& t_text = fields[column_of[t_index]];
    if (prev_t_line != 0 && !(t.back() > t[t.size() - 2]))
      fail(column_of[t_index] + 1, "column '" + mapping[t_index].source + "': time not strictly increasing: " +
                                       t_text + " after " + prev_t_text + " at line " + std::to_string(prev_t_line));
    prev_t_text = t_text;
    prev_t_line = lines.line_number();
  }
  if (out.channels[kT].size() < kMinRows)
    throw CsvError(source, lines.line_number(), 0, "need at least " + std::to_string(kMinRows) +
                                                       " data rows, found " + std::to_string(out.channels[kT].size()));
  return out;
}

}  // namespace knoblab::interchange
