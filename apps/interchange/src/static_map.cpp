#include "knoblab/interchange/static_map.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "knoblab/interchange/capture.hpp"

namespace knoblab::interchange {

void validate(const StaticMap& m) {
  if (m.torque.size() != m.theta.size())
    throw std::invalid_argument("static map: torque has " + std::to_string(m.torque.size()) + " values, theta " +
                                std::to_string(m.theta.size()));
  if (m.size() < 3) throw std::invalid_argument("static map: needs at least 3 points, has " + std::to_string(m.size()));
  for (const auto* v : {&m.theta, &m.torque})
    for (std::size_t i = 0; i < v->size(); ++i)
      if (!std::isfinite((*v)[i]) || std::abs((*v)[i]) > kMaxMagnitude)
        throw std::invalid_argument(std::string("static map: ") + (v == &m.theta ? "theta" : "torque") + " row " +
                                    std::to_string(i) + " is not finite or beyond ±1e12");
  for (std::size_t i = 1; i < m.size(); ++i)
    if (!(m.theta[i] > m.theta[i - 1]))
      throw std::invalid_argument("static map: theta is not strictly increasing at row " + std::to_string(i));
  if (!(m.theta.back() - m.theta.front() < 2 * std::numbers::pi))
    throw std::invalid_argument("static map: theta spans a whole revolution or more; a map holds one revolution");
}

}  // namespace knoblab::interchange
