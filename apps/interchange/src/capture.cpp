#include "knoblab/interchange/capture.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace knoblab::interchange {

const std::string* Capture::find_metadata(std::string_view key) const {
  for (const auto& [k, v] : metadata)
    if (k == key) return &v;
  return nullptr;
}

void validate(const Capture& c) {
  const std::size_t n = c.size();
  const auto check_length = [&](const std::vector<double>& v, std::string_view name) {
    if (v.size() != n)
      throw std::invalid_argument("channel '" + std::string(name) + "' has " +
                                  std::to_string(v.size()) + " values, t has " +
                                  std::to_string(n));
  };
  check_length(c.theta, "theta");
  check_length(c.omega, "omega");
  check_length(c.alpha, "alpha");
  check_length(c.torque, "torque");
  if (c.has_command) check_length(c.command, "command");
  if (!c.flags.empty() && c.flags.size() != n)
    throw std::invalid_argument("flags has " + std::to_string(c.flags.size()) + " values, t has " +
                                std::to_string(n));
  if (n < 3)
    throw std::invalid_argument("a capture needs at least 3 rows, has " + std::to_string(n));

  const auto check_finite = [&](const std::vector<double>& v, std::string_view name) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i]))
        throw std::invalid_argument("channel '" + std::string(name) + "' row " +
                                    std::to_string(i) + " is not finite");
      if (std::abs(v[i]) > kMaxMagnitude)
        throw std::invalid_argument("channel '" + std::string(name) + "' row " + std::to_string(i) +
                                    " is beyond ±1e12: no measurement in SI units is that large");
    }
  };
  check_finite(c.t, "t");
  check_finite(c.theta, "theta");
  check_finite(c.omega, "omega");
  check_finite(c.alpha, "alpha");
  check_finite(c.torque, "torque");
  if (c.has_command) check_finite(c.command, "command");

  for (std::size_t i = 1; i < n; ++i)
    if (!(c.t[i] > c.t[i - 1]))
      throw std::invalid_argument("t is not strictly increasing at row " + std::to_string(i));
}

}  // namespace knoblab::interchange
