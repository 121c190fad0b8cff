// Deterministic data shaped like the thesis' studies: continuous scores
// (times, biometrics) and 1–9 self-report ratings (SAM), which tie often.
// Values are rounded to 1e-3 so the CSV decimals read back identically in
// every reference.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace knoblab::stats::test {

inline double round3(double v) { return std::round(v * 1000) / 1000; }

// n subjects × k conditions: a subject offset, a condition effect and noise
// whose spread grows with the condition (unequal variances and a shared
// drift make the covariance non-spherical, so ε < 1).
inline std::vector<std::vector<double>> scores(std::size_t n, std::size_t k, unsigned seed,
                                               double effect = 0.4, double spread_growth = 0.6) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<std::vector<double>> y(n, std::vector<double>(k));
  for (auto& row : y) {
    const double subject = 2 * normal(rng), drift = normal(rng);
    for (std::size_t j = 0; j < k; ++j) {
      const double jd = static_cast<double>(j);
      row[j] = round3(10 + subject + effect * jd + drift * spread_growth * jd +
                      (1 + spread_growth * jd) * normal(rng));
    }
  }
  return y;
}

// n subjects × k conditions of ratings 1..9 around a condition trend.
inline std::vector<std::vector<double>> ratings(std::size_t n, std::size_t k, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<std::vector<double>> y(n, std::vector<double>(k));
  for (auto& row : y) {
    const double subject = normal(rng);
    for (std::size_t j = 0; j < k; ++j)
      row[j] = std::clamp(std::round(5 + subject + 0.5 * static_cast<double>(j) - 1.5 + 1.5 * normal(rng)),
                          1.0, 9.0);
  }
  return y;
}

// Column j of a subjects × conditions table.
inline std::vector<double> column(const std::vector<std::vector<double>>& y, std::size_t j) {
  std::vector<double> c;
  for (const auto& row : y) c.push_back(row[j]);
  return c;
}

}  // namespace knoblab::stats::test
