#include "convert_arrays.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "args.hpp"
#include "knoblab/interchange/capture.hpp"
#include "knoblab/interchange/number_text.hpp"

namespace knoblab::cli::convert {

using interchange::MatArray;
using interchange::shortest;

namespace {

// Median spacing of time stamps within segments: the assumed pause between
// segments whose clocks restart.
double median_interval(const MatArray& a, std::size_t t_row) {
  std::vector<double> dt;
  for (std::size_t j = 0; j < a.cols(); ++j) {
    const auto& t = a.cell(t_row, j).values;
    for (std::size_t i = 1; i < t.size(); ++i) dt.push_back(t[i] - t[i - 1]);
  }
  if (dt.empty()) throw std::runtime_error("no segment has two samples to space the segments by");
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

}  // namespace

std::vector<int> parse_channel_list(const std::string& text) {
  std::vector<int> cols;
  std::array<bool, kChannelCount> seen{};
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    std::string name = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    if (name == "-") {
      cols.push_back(kSkip);
    } else {
      const auto it = std::find(interchange::kChannelNames.begin(), interchange::kChannelNames.end(), name);
      if (it == interchange::kChannelNames.end())
        throw UsageError("--columns: unknown channel '" + name +
                         "' (names: t, theta, omega, alpha, torque, command, or - to skip)");
      const auto ch = static_cast<std::size_t>(it - interchange::kChannelNames.begin());
      if (seen[ch]) throw UsageError("--columns: '" + name + "' given twice");
      seen[ch] = true;
      cols.push_back(static_cast<int>(ch));
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (!seen[kT] || !seen[kTheta] || !seen[kTorque])
    throw UsageError("--columns must name t, theta and torque");
  return cols;
}

Channels from_matrix(const MatArray& a, const std::vector<int>& cols, const std::string& what) {
  const std::size_t n = cols.size();
  if (a.dims.size() != 2) throw std::runtime_error(what + " is " + a.describe() + "; expected a 2-D matrix");
  const bool by_rows = a.rows() == n;
  if (!by_rows && a.cols() != n)
    throw std::runtime_error(what + " is " + a.describe() + ": neither its rows nor its columns match the " +
                             std::to_string(n) + " names in --columns");
  const std::size_t samples = by_rows ? a.cols() : a.rows();
  Channels out;
  for (std::size_t k = 0; k < n; ++k) {
    if (cols[k] == kSkip) continue;
    auto& v = out[static_cast<std::size_t>(cols[k])];
    v.resize(samples);
    for (std::size_t i = 0; i < samples; ++i) v[i] = by_rows ? a.at(k, i) : a.at(i, k);
  }
  return out;
}

Channels from_cells(const MatArray& a, const std::vector<int>& cols, const std::string& what, bool restart) {
  const std::size_t n = cols.size();
  if (a.dims.size() != 2 || a.rows() != n)
    throw std::runtime_error(what + " is " + a.describe() + ": --columns names " + std::to_string(n) +
                             " rows, one per row of cells");
  const auto t_row = static_cast<std::size_t>(std::find(cols.begin(), cols.end(), kT) - cols.begin());
  const double pause = restart ? median_interval(a, t_row) : 0.0;
  Channels out;
  std::vector<double>& t = out[kT];
  for (std::size_t j = 0; j < a.cols(); ++j) {
    const std::string seg = "segment " + std::to_string(j + 1) + " (cell column " + std::to_string(j + 1) + ")";
    std::size_t len = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (cols[k] == kSkip) continue;  // whatever a skipped row holds (e.g. a setpoint) is ignored
      const MatArray& c = a.cell(k, j);
      if (!c.is_numeric())
        throw std::runtime_error(what + ": " + seg + ", row " + std::to_string(k + 1) + ": expected numbers, found " +
                                 c.describe());
      if (k != t_row && c.numel() != a.cell(t_row, j).numel())
        throw std::runtime_error(what + ": " + seg + ": row " + std::to_string(k + 1) + " has " +
                                 std::to_string(c.numel()) + " values, the t row " + std::to_string(t_row + 1) +
                                 " has " + std::to_string(a.cell(t_row, j).numel()));
      len = c.numel();
    }
    if (len == 0) continue;
    const auto& seg_t = a.cell(t_row, j).values;
    double offset = 0.0;
    std::size_t first = 0;
    if (!t.empty() && restart) {
      offset = t.back() + pause;  // the segment's clock zero, one median interval after the last sample
    } else if (!t.empty() && seg_t[0] == t.back()) {
      first = 1;  // the boundary sample recorded twice
    } else if (!t.empty() && seg_t[0] < t.back()) {
      throw std::runtime_error(what + ": " + seg + " starts at t = " + shortest(seg_t[0]) +
                               " s, before the previous segment ends (t = " + shortest(t.back()) +
                               " s); if each segment's clock starts again, use --segment-time restart");
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (cols[k] == kSkip) continue;
      const auto& v = a.cell(k, j).values;
      auto& dst = out[static_cast<std::size_t>(cols[k])];
      for (std::size_t i = first; i < v.size(); ++i) dst.push_back(k == t_row ? v[i] + offset : v[i]);
    }
  }
  return out;
}

std::size_t unwrap(std::vector<double>& x, double period) {
  std::size_t jumps = 0;
  double shift = 0.0, prev = x.empty() ? 0.0 : x[0];
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double raw = x[i];
    const double turns = std::round((raw - prev) / period);
    if (turns != 0.0) {
      shift -= turns * period;
      ++jumps;
    }
    prev = raw;
    x[i] = raw + shift;
  }
  return jumps;
}

}  // namespace knoblab::cli::convert
