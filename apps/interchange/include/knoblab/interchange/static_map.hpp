// A static map: the torque that holds the knob still at each position over
// one revolution (e.g. the ODrive cogging maps: holding current at each
// encoder position). Not a time series: no time stamps, no velocity, so
// nothing that needs them (fit, import, discrepancy) takes one.
//
// As interchange CSV it is marked by a `# kind: static-map` metadata line and
// holds exactly the columns theta and torque (csv.hpp reads and writes it).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace knoblab::interchange {

inline constexpr std::string_view kKindKey = "kind";
inline constexpr std::string_view kStaticMapKind = "static-map";

struct StaticMap {
  // `# key: value` lines, in file order, without the kind line (implied).
  std::vector<std::pair<std::string, std::string>> metadata;
  std::vector<double> theta;   // rad, strictly increasing, within one revolution
  std::vector<double> torque;  // N·m holding torque at each theta

  std::size_t size() const { return theta.size(); }
};

// Throws std::invalid_argument naming the first problem: unequal lengths,
// fewer than 3 points, a value not finite or beyond ±1e12, theta not
// strictly increasing or spanning a whole revolution or more.
void validate(const StaticMap& map);

}  // namespace knoblab::interchange
