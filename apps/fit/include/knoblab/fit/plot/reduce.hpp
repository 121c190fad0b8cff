// Fewer points for a figure that shows the same: even thinning of a cloud, a
// time series by its envelope, a noisy band smoothed along its axis.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "knoblab/fit/plot/figure.hpp"

namespace knoblab::fit::plot {

// At most m indices spread evenly over [0, n), in order, the first and the
// last among them (all of them when n ≤ m).
std::vector<std::size_t> thin(std::size_t n, std::size_t m);

// The indices of `key` in ascending order of their values (stable).
std::vector<std::size_t> sorted_by(const std::vector<double>& key);

// A centred moving average of v taken in `order` (a window of n/200), over
// its finite values (NaN where a window has none); in order's positions.
std::vector<double> smoothed_along(const std::vector<double>& v, const std::vector<std::size_t>& order);

using Values = std::function<double(std::size_t)>;

// A time series as at most 2·buckets points keeping its envelope: the
// smallest and the largest value of each bucket, in time order (striding
// would alias a fast signal into false beats). Appended to s.x, s.y.
void minmax_series(Series& s, const std::vector<double>& t, std::size_t buckets, const Values& y);

// A band's edge over time: the largest y of each bucket at the bucket's
// middle, so a fast-varying band shows as its envelope.
void envelope_series(Series& s, const std::vector<double>& t, std::size_t buckets, const Values& y);

}  // namespace knoblab::fit::plot
