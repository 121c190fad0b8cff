#include "knoblab/fit/plot/reduce.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace knoblab::fit::plot {

std::vector<std::size_t> thin(std::size_t n, std::size_t m) {
  std::vector<std::size_t> idx;
  if (n <= m) {
    idx.resize(n);
    std::iota(idx.begin(), idx.end(), std::size_t{0});
    return idx;
  }
  idx.reserve(m);
  if (m == 1) return {0};
  for (std::size_t k = 0; k < m; ++k) idx.push_back(k * (n - 1) / (m - 1));  // the first and the last among them
  return idx;
}

std::vector<std::size_t> sorted_by(const std::vector<double>& key) {
  std::vector<std::size_t> order(key.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  return order;
}

std::vector<double> smoothed_along(const std::vector<double>& v, const std::vector<std::size_t>& order) {
  const std::size_t n = order.size();
  std::vector<double> prefix(n + 1, 0.0);
  std::vector<std::size_t> finite(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const double x = v[order[k]];
    const bool ok = std::isfinite(x);
    prefix[k + 1] = prefix[k] + (ok ? x : 0.0);
    finite[k + 1] = finite[k] + (ok ? 1 : 0);
  }
  const std::size_t half = std::max<std::size_t>(1, n / 400);
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k >= half ? k - half : 0;
    const std::size_t hi = std::min(n, k + half + 1);
    const std::size_t count = finite[hi] - finite[lo];
    out[k] = count == 0 ? std::numeric_limits<double>::quiet_NaN()
                        : (prefix[hi] - prefix[lo]) / static_cast<double>(count);
  }
  return out;
}

void minmax_series(Series& s, const std::vector<double>& t, std::size_t buckets, const Values& y) {
  const std::size_t n = t.size();
  if (n <= 2 * buckets) {
    for (std::size_t i = 0; i < n; ++i) s.x.push_back(t[i]), s.y.push_back(y(i));
    return;
  }
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t lo = b * n / buckets, hi = (b + 1) * n / buckets;
    std::size_t imin = hi, imax = hi;
    for (std::size_t i = lo; i < hi; ++i) {
      const double v = y(i);
      if (!std::isfinite(v)) continue;
      if (imin == hi || v < y(imin)) imin = i;
      if (imax == hi || v > y(imax)) imax = i;
    }
    if (imin == hi) continue;  // nothing finite in this bucket
    for (const std::size_t i : {std::min(imin, imax), std::max(imin, imax)}) s.x.push_back(t[i]), s.y.push_back(y(i));
  }
}

void envelope_series(Series& s, const std::vector<double>& t, std::size_t buckets, const Values& y) {
  const std::size_t n = t.size();
  buckets = std::min(buckets, n);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t lo = b * n / buckets, hi = (b + 1) * n / buckets;
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t i = lo; i < hi; ++i)
      if (std::isfinite(y(i))) top = std::max(top, y(i));
    s.x.push_back(t[(lo + hi - 1) / 2]);
    s.y.push_back(std::isfinite(top) ? top : std::numeric_limits<double>::quiet_NaN());
  }
}

}  // namespace knoblab::fit::plot
