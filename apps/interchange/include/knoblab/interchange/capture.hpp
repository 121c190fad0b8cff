// One captured (or simulated) knob run: time-aligned channels in SI units.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace knoblab::interchange {

// Column names of the CSV format's channels, in the order write_csv emits
// them.
inline constexpr std::array<std::string_view, 6> kChannelNames = {
    "t", "theta", "omega", "alpha", "torque", "command"};
// The optional last column: each row's SampleFlag bits as an unsigned
// decimal integer (not a channel: no unit, never derived).
inline constexpr std::string_view kFlagsColumn = "flags";

// No real measurement in SI units comes near this (1e12 rad, rad/s, rad/s²,
// N·m, s, V): a value beyond it is a corrupted file or a wrong unit, and it
// would overflow the sums and squares that fits and summaries take.
inline constexpr double kMaxMagnitude = 1e12;

struct Capture {
  // `# key: value` lines, in file order. An empty key is a free comment.
  std::vector<std::pair<std::string, std::string>> metadata;

  std::vector<double> t;       // s, strictly increasing
  std::vector<double> theta;   // rad
  std::vector<double> omega;   // rad/s
  std::vector<double> alpha;   // rad/s²
  std::vector<double> torque;  // N·m
  std::vector<double> command; // V; empty unless has_command
  // SampleFlag bits per row (what the loop did: amplifier on, e-stop, fault,
  // torque limited); empty when unknown (a CSV without a flags column).
  std::vector<std::uint32_t> flags;

  bool has_command = false;
  bool omega_derived = false;  // omega was absent from the file
  bool alpha_derived = false;  // alpha was absent from the file

  std::size_t size() const { return t.size(); }

  // Value of the first metadata entry with this key, or nullptr.
  const std::string* find_metadata(std::string_view key) const;
};

// Throws std::invalid_argument naming the first problem: channels (or
// non-empty flags) of unequal length, fewer than 3 rows, non-finite values,
// t not strictly increasing.
// Everything that passes can be written and read back by the CSV code.
void validate(const Capture& capture);

}  // namespace knoblab::interchange
