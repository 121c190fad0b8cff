#include "convert_map.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace knoblab::cli::convert {

MapResult map_over_rev(const interchange::MatArray& var, const std::string& what, double torque_scale,
                       std::optional<double> missing) {
  if (!var.is_numeric() || var.dims.size() != 2 || (var.rows() != 1 && var.cols() != 1))
    throw std::runtime_error(what + " is " + var.describe() +
                             "; --map-over-rev reads a vector of values, one per position over one revolution");
  MapResult r;
  r.positions = var.numel();
  const double step = 2 * std::numbers::pi / static_cast<double>(r.positions);
  for (std::size_t i = 0; i < r.positions; ++i) {
    const double v = var.values[i];
    // NaN marks a missing value only when NaN was asked for: NaN never equals itself.
    if (missing && (v == *missing || (std::isnan(*missing) && std::isnan(v)))) {
      ++r.missing;
      continue;
    }
    if (!std::isfinite(v))
      throw std::runtime_error(what + ": position " + std::to_string(i) + " holds " + std::to_string(v) +
                               (missing ? "" : "; if it marks a position not measured, add --missing nan"));
    r.map.theta.push_back(step * static_cast<double>(i));
    r.map.torque.push_back(v * torque_scale);
  }
  if (r.map.size() < 3)
    throw std::runtime_error(what + ": only " + std::to_string(r.map.size()) + " of " + std::to_string(r.positions) +
                             " positions measured; a static map needs at least 3");
  return r;
}

}  // namespace knoblab::cli::convert
