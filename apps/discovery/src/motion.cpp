#include "motion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace knoblab::discovery::detail {

std::size_t count_reversals(std::span<const double> theta, double travel) {
  if (theta.empty()) return 0;
  std::size_t n = 0;
  int direction = 0;  // of the stroke under way: +1, −1, 0 before the first
  double turn = theta[0], lo = theta[0], hi = theta[0];  // the stroke's extreme; the range so far
  for (const double x : theta) {
    if (direction == 0) {
      lo = std::min(lo, x), hi = std::max(hi, x);
      if (hi - x > travel) direction = -1, turn = x;  // the first stroke's direction, once it has one
      if (x - lo > travel) direction = 1, turn = x;
      continue;
    }
    if ((x - turn) * direction > 0) {
      turn = x;  // further the same way
    } else if (std::abs(x - turn) > travel) {
      ++n;
      direction = -direction;
      turn = x;
    }
  }
  return n;
}

std::string effect_span(const fit::FitData& d, std::span<const std::size_t> rows,
                        const std::vector<double>& before, const std::vector<double>& after) {
  std::vector<double> cumulative(rows.size(), 0.0);
  double total = 0.0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const double change = before[j] - after[j];
    if (std::isfinite(change)) total += change * change;
    cumulative[j] = total;
  }
  if (!(total > 0.0)) return "";
  const auto at = [&](double share) {
    return static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), share * total) -
                                    cumulative.begin());
  };
  const std::size_t from = at(0.05), to = std::min(at(0.95), rows.size() - 1);
  double lo = d.theta[rows[from]], hi = lo;
  for (std::size_t j = from; j <= to; ++j) lo = std::min(lo, d.theta[rows[j]]), hi = std::max(hi, d.theta[rows[j]]);
  const fit::AxisUnits& u = fit::units(d.axis);
  char buf[160];
  std::snprintf(buf, sizeof buf, "t %.3g–%.3g s, %s %.3g…", d.t[rows[from]], d.t[rows[to]],
                std::string(u.theta).c_str(), u.position(lo));
  return buf + u.position.with(hi);
}

}  // namespace knoblab::discovery::detail
