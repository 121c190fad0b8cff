// SosCascade state handling and the offline filters (scipy sosfilt,
// sosfiltfilt).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "knoblab/model/filters.hpp"

namespace knoblab::model {

SosCascade::SosCascade(std::span<const Sos> sections) {
  if (sections.size() > kMaxSections)
    throw std::invalid_argument("SosCascade holds at most 10 sections");
  std::copy(sections.begin(), sections.end(), sections_.begin());
  count_ = sections.size();
}

void SosCascade::reset() noexcept { state_ = {}; }

// Each section's steady state for its own constant input u, where u is x
// times the DC gain of the sections before it (scipy sosfilt_zi):
// y = g·u, z0 = y − b0·u, z1 = b2·u − a2·y.
void SosCascade::reset_to_steady_state(double x) noexcept {
  double u = x;
  for (std::size_t i = 0; i < count_; ++i) {
    const Sos& s = sections_[i];
    const double y = u * (s.b0 + s.b1 + s.b2) / (1.0 + s.a1 + s.a2);
    state_[i] = {y - s.b0 * u, s.b2 * u - s.a2 * y};
    u = y;
  }
}

std::complex<double> SosCascade::response(double f_hz, double fs_hz) const noexcept {
  const std::complex<double> zi = std::polar(1.0, -2.0 * std::numbers::pi * f_hz / fs_hz);
  std::complex<double> h = 1.0;
  for (std::size_t i = 0; i < count_; ++i) {
    const Sos& s = sections_[i];
    h *= (s.b0 + zi * (s.b1 + zi * s.b2)) / (1.0 + zi * (s.a1 + zi * s.a2));
  }
  return h;
}

double SosCascade::dc_gain() const noexcept {
  double g = 1.0;
  for (std::size_t i = 0; i < count_; ++i) {
    const Sos& s = sections_[i];
    g *= (s.b0 + s.b1 + s.b2) / (1.0 + s.a1 + s.a2);
  }
  return g;
}

std::vector<double> sosfilt(const SosCascade& filter, std::span<const double> x) {
  SosCascade f = filter;
  f.reset();
  std::vector<double> y(x.size());
  std::transform(x.begin(), x.end(), y.begin(), [&f](double v) { return f.process(v); });
  return y;
}

// scipy: ntaps = 2·n_sections + 1 − min(#(b2 == 0), #(a2 == 0)), padlen = 3·ntaps.
std::size_t sosfiltfilt_padlen(const SosCascade& filter) noexcept {
  std::size_t zero_b2 = 0, zero_a2 = 0;
  for (const Sos& s : filter.sections()) {
    zero_b2 += s.b2 == 0.0 ? 1u : 0u;
    zero_a2 += s.a2 == 0.0 ? 1u : 0u;
  }
  const std::size_t ntaps = 2 * filter.size() + 1 - std::min(zero_b2, zero_a2);
  return 3 * ntaps;
}

std::vector<double> sosfiltfilt(const SosCascade& filter, std::span<const double> x) {
  const std::size_t n = x.size();
  const std::size_t pad = sosfiltfilt_padlen(filter);
  if (n <= pad) throw std::invalid_argument("sosfiltfilt: input must be longer than padlen");

  // Odd extension: mirror about the end points, 2·x[0] − x[pad..1] etc.
  std::vector<double> ext(n + 2 * pad);
  for (std::size_t i = 0; i < pad; ++i) {
    ext[i] = 2.0 * x[0] - x[pad - i];
    ext[pad + n + i] = 2.0 * x[n - 1] - x[n - 2 - i];
  }
  std::copy(x.begin(), x.end(), ext.begin() + static_cast<std::ptrdiff_t>(pad));

  SosCascade f = filter;
  f.reset_to_steady_state(ext.front());
  for (double& v : ext) v = f.process(v);
  f.reset_to_steady_state(ext.back());
  for (auto it = ext.rbegin(); it != ext.rend(); ++it) *it = f.process(*it);

  return {ext.begin() + static_cast<std::ptrdiff_t>(pad),
          ext.begin() + static_cast<std::ptrdiff_t>(pad + n)};
}

}  // namespace knoblab::model
