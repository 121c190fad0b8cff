#include "knoblab/fit/plot/ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace knoblab::fit::plot {

namespace {

constexpr double kSteps[] = {1.0, 2.0, 2.5, 5.0, 10.0};

std::string label(double v, int decimals, bool exponent) {
  char buf[48];
  if (exponent) std::snprintf(buf, sizeof buf, "%.3g", v);
  else std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s.starts_with("-")) {
    // "-0.0" is zero; other negatives get a true minus sign.
    if (std::stod(s) == 0.0) s.erase(0, 1);
    else s.replace(0, 1, "\u2212");
  }
  return s;
}

}  // namespace

Ticks nice_ticks(double lo, double hi, std::size_t target) {
  Ticks t;
  if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi)) return t;
  const double raw = (hi - lo) / static_cast<double>(std::max<std::size_t>(1, target));
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = decade * 10.0;
  for (const double m : kSteps) {
    if (m * decade >= raw * 0.999) {
      step = m * decade;
      break;
    }
  }
  // Fewer than two ticks inside: the next smaller step.
  const auto count = [&](double s) { return std::floor(hi / s + 1e-9) - std::ceil(lo / s - 1e-9) + 1.0; };
  while (count(step) < 2.0 && step > raw * 1e-3) step /= 2.0;
  t.step = step;
  // As many decimals as the step has: 25 none, 2.5 one, 0.05 two.
  int decimals = 0;
  while (decimals < 12 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) >
                              1e-6 * step * std::pow(10.0, decimals))
    ++decimals;
  const double biggest = std::max(std::abs(lo), std::abs(hi));
  const bool exponent = biggest >= 1e6 || decimals > 5;
  for (double k = std::ceil(lo / step - 1e-9); k <= std::floor(hi / step + 1e-9); k += 1.0) {
    const double v = k * step;
    t.at.push_back(v);
    t.labels.push_back(label(v, decimals, exponent));
  }
  return t;
}

Range padded(double lo, double hi, double pad) {
  if (!(lo <= hi) || !std::isfinite(lo) || !std::isfinite(hi)) return {-1.0, 1.0};
  double span = hi - lo;
  if (span <= 1e-12 * std::max(1.0, std::abs(hi))) {
    span = std::max(std::abs(hi) * 0.2, 1e-3);
    return {lo - span / 2, hi + span / 2};
  }
  return {lo - pad * span, hi + pad * span};
}

}  // namespace knoblab::fit::plot
