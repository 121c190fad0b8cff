// Cubic interpolating spline: the waveform editor's curve (thesis §5.3) and
// the f(θ), f(t) of the prototyper tiles (Eq. 19/20).
//
// Same curve as scipy.interpolate.CubicSpline with bc_type='natural' (second
// derivative 0 at both ends; evaluation outside the knots extends the end
// cubics) or bc_type='periodic' (first and second derivatives match across
// the ends; evaluation outside the knots wraps). Evaluation does a binary
// search and never allocates.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

namespace knoblab::model {

enum class SplineBoundary { kNatural, kPeriodic };

namespace detail {
// Value part of a scalar: the number itself, or .a of a ceres::Jet-like type.
template <typename T>
double scalar_value(const T& x) {
  if constexpr (std::is_arithmetic_v<T>) return static_cast<double>(x);
  else return x.a;
}
}  // namespace detail

class CubicSpline {
 public:
  // An empty spline; evaluates to 0.
  CubicSpline() = default;
  // Knots x strictly increasing, at least 2. Periodic needs y.front() ==
  // y.back() (to 1e-9 relative). Throws std::invalid_argument otherwise.
  CubicSpline(std::span<const double> x, std::span<const double> y,
              SplineBoundary bc = SplineBoundary::kNatural);

  template <typename T>
  T operator()(const T& x) const {
    if (coef_.empty()) return T(0);
    double shift = 0.0;
    const std::size_t i = segment(detail::scalar_value(x), shift);
    const std::array<double, 4>& c = coef_[i];
    const T dx = x - T(x_[i] + shift);
    return T(c[0]) + dx * (T(c[1]) + dx * (T(c[2]) + dx * T(c[3])));
  }
  // First derivative dy/dx.
  double derivative(double x) const noexcept;

  bool empty() const noexcept { return coef_.empty(); }
  double x_min() const noexcept { return x_.empty() ? 0.0 : x_.front(); }
  double x_max() const noexcept { return x_.empty() ? 0.0 : x_.back(); }
  std::span<const double> knots() const noexcept { return x_; }
  SplineBoundary boundary() const noexcept { return bc_; }

 private:
  // Segment holding x; for periodic splines also the multiple of the period
  // that was removed to bring x into [x_min, x_max).
  std::size_t segment(double x, double& shift) const noexcept;

  std::vector<double> x_;
  std::vector<std::array<double, 4>> coef_;  // y, y', y''/2, y'''/6 at x_[i]
  SplineBoundary bc_ = SplineBoundary::kNatural;
};

}  // namespace knoblab::model
