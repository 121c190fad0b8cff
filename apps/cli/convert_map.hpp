// knoblab convert --map-over-rev: a vector of values over one revolution
// (position i of N at theta = 2*pi*i/N), such as the ODrive cogging maps, to
// a static map. Positions holding the --missing value were not measured and
// are left out; nothing is interpolated and no time is invented.
#pragma once

#include <optional>
#include <string>

#include "knoblab/interchange/mat5.hpp"
#include "knoblab/interchange/static_map.hpp"

namespace knoblab::cli::convert {

struct MapResult {
  interchange::StaticMap map;
  std::size_t positions = 0;  // N, the array's length
  std::size_t missing = 0;    // positions left out
};

// Throws std::runtime_error when `var` is not a real numeric vector, or
// when fewer than 3 positions remain.
MapResult map_over_rev(const interchange::MatArray& var, const std::string& what, double torque_scale,
                       std::optional<double> missing);

}  // namespace knoblab::cli::convert
