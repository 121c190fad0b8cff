// CSV files other tools write (their own column names and units, comma,
// semicolon or tab delimited) read into knoblab's channels in SI units,
// through a column mapping such as
//
//   time_ms=t:ms,angle_deg=theta:deg,torque_mNm=torque:mN*m,current_A=command:*2.5
//
// Each entry is SOURCE=CHANNEL[:UNIT]: the file's column SOURCE (as its
// header spells it) holds CHANNEL (t, theta, omega, alpha, torque, command)
// in UNIT; CHANNEL[:UNIT] alone when the column already has the channel's
// name. No unit means SI. `*FACTOR` as the unit multiplies by FACTOR to get
// SI (e.g. current in A to torque in N·m: `*0.0551`). Columns not named are
// ignored. t, theta and torque are required.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/interchange/capture.hpp"

namespace knoblab::interchange {

// A unit a channel may be given in: SI value = value × scale. per_rev: how
// many of it make one revolution (position units only; 0 otherwise).
struct Unit {
  std::string name;
  double scale = 1.0;
  double per_rev = 0.0;
};

// The units each channel accepts, by channel index (kChannelNames order).
// counts_per_rev > 0 adds "counts" (and counts/s, counts/s^2).
std::vector<Unit> channel_units(std::size_t channel, double counts_per_rev);

struct ColumnMapping {
  std::string source;    // the column's name in the file's header
  std::size_t channel;   // index into kChannelNames
  Unit unit;
};

// Parses the mapping text; throws std::invalid_argument saying which entry
// is wrong and what is allowed (unknown channel or unit, a channel twice,
// counts without counts_per_rev, t, theta or torque missing).
std::vector<ColumnMapping> parse_column_mapping(std::string_view text, double counts_per_rev);

// The mapping written back as text (for the converted file's metadata).
std::string mapping_text(const std::vector<ColumnMapping>& mapping);

struct MappedCsv {
  std::array<std::vector<double>, kChannelNames.size()> channels;  // SI; empty = not mapped
  char delimiter = ',';
  std::vector<std::string> ignored;  // header names not mapped
};

// Reads `path`: optional '#' comment lines, one header line, then rows.
// delimiter is ',', ';', '\t', or 0 to take the one the header uses. Fields
// may be double-quoted ("a,b", "" for a quote). Throws CsvError naming
// file:line:column for a mapped column missing from the header, a short or
// long row, a field that is not a number (a decimal comma gets a hint), a
// value beyond ±1e12 once in SI, or t not strictly increasing.
MappedCsv read_mapped_csv(const std::filesystem::path& path, const std::vector<ColumnMapping>& mapping,
                          char delimiter = 0);

}  // namespace knoblab::interchange
