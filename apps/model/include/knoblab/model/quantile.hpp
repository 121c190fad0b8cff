// The q-quantile (0 ≤ q ≤ 1) of a sample as its order statistic at
// ⌊q·(n − 1)⌋, without interpolation: what robust scales (the median absolute
// deviation), thresholds and static levels here need. NaN for no values.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace knoblab::model {

inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

}  // namespace knoblab::model
