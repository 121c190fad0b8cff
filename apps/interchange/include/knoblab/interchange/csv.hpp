// The knoblab interchange CSV. Outside benchmarks read it too: keep it stable.
//
//   # key: value            optional metadata lines, kept in order
//   t,theta,torque[,omega][,alpha][,command][,flags]   one header, any column order
//   0.0001,0.12,0.003       rows, SI units, '.' decimal point
//
// t, theta and torque are required. Missing omega/alpha are derived from
// theta/omega (see derive.hpp) and flagged in the Capture. flags holds each
// row's SampleFlag bits as an unsigned integer. Whitespace around
// fields, CRLF line ends, a UTF-8 BOM and trailing empty lines are tolerated;
// everything else that is off is a CsvError naming line and column.
//
// A `# kind: static-map` line makes the file a static map (static_map.hpp):
// columns theta and torque only, theta strictly increasing within one
// revolution. read_recording gives either kind; read_csv refuses a static
// map, saying what takes one.
#pragma once

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

#include "knoblab/interchange/capture.hpp"
#include "knoblab/interchange/static_map.hpp"

namespace knoblab::interchange {

// Limits that keep a garbage file from costing more than a little memory.
inline constexpr std::size_t kMaxLineBytes = 64 * 1024;
inline constexpr std::size_t kMaxMetadataBytes = 1024 * 1024;
inline constexpr std::size_t kMinRows = 3;

class CsvError : public std::runtime_error {
 public:
  // what() is "source:line:column: reason" ("source:line: reason" when the
  // error concerns the whole line, "source: reason" when line is 0).
  CsvError(std::string source, std::size_t line, std::size_t column, std::string reason);

  const std::string& source() const { return source_; }
  std::size_t line() const { return line_; }      // 1-based; 0 = whole file
  std::size_t column() const { return column_; }  // 1-based field; 0 = whole line
  const std::string& reason() const { return reason_; }

 private:
  std::string source_;
  std::size_t line_;
  std::size_t column_;
  std::string reason_;
};

// Parse a capture; source_name only labels error messages. A static map is
// a CsvError at its kind line.
Capture parse_csv(std::istream& in, std::string_view source_name);
Capture read_csv(const std::filesystem::path& path);

// Either kind of file: a recording over time or a static map.
using Recording = std::variant<Capture, StaticMap>;
Recording parse_recording(std::istream& in, std::string_view source_name);
Recording read_recording(const std::filesystem::path& path);

// Writes metadata, header and rows (ω, α only when not derived; flags only
// when some row has a flag set: all-zero flags read back the same without
// the column); doubles in
// shortest round-trip form, so read_csv(write_csv(c)) reproduces every value
// bit for bit. Throws
// std::invalid_argument for a capture validate() rejects or for metadata a
// single comment line cannot hold.
void write_csv(const Capture& capture, std::ostream& out);

// Same, to a sibling temp file that is fsynced and renamed over `path`: a
// crash leaves either the old file or the complete new one, never a part.
// I/O failures throw std::system_error; the temp file is removed.
void write_csv(const Capture& capture, const std::filesystem::path& path);

// A static map: the kind line, its metadata, then theta,torque rows; the
// same guarantees as write_csv. Metadata may not hold a 'kind' key.
void write_static_map(const StaticMap& map, std::ostream& out);
void write_static_map(const StaticMap& map, const std::filesystem::path& path);

}  // namespace knoblab::interchange
