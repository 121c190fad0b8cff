// Derivative on irregular time stamps (three-point Lagrange differences).
#include <stdexcept>

#include "knoblab/model/filters.hpp"

namespace knoblab::model {

std::vector<double> derivative(std::span<const double> t, std::span<const double> x) {
  if (t.size() != x.size()) throw std::invalid_argument("derivative: t and x differ in size");
  const std::size_t n = t.size();
  for (std::size_t i = 1; i < n; ++i)
    if (!(t[i] > t[i - 1])) throw std::invalid_argument("derivative: t must increase strictly");
  std::vector<double> dx(n, 0.0);
  if (n < 2) return dx;
  if (n == 2) {
    dx[0] = dx[1] = (x[1] - x[0]) / (t[1] - t[0]);
    return dx;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h1 = t[i] - t[i - 1];
    const double h2 = t[i + 1] - t[i];
    dx[i] = (-h2 / (h1 * (h1 + h2))) * x[i - 1] + ((h2 - h1) / (h1 * h2)) * x[i] +
            (h1 / (h2 * (h1 + h2))) * x[i + 1];
  }
  {
    const double h1 = t[1] - t[0];
    const double h2 = t[2] - t[1];
    dx[0] = (-(2.0 * h1 + h2) / (h1 * (h1 + h2))) * x[0] + ((h1 + h2) / (h1 * h2)) * x[1] +
            (-h1 / (h2 * (h1 + h2))) * x[2];
  }
  {
    const double h1 = t[n - 2] - t[n - 3];
    const double h2 = t[n - 1] - t[n - 2];
    dx[n - 1] = (h2 / (h1 * (h1 + h2))) * x[n - 3] + (-(h1 + h2) / (h1 * h2)) * x[n - 2] +
                ((2.0 * h2 + h1) / (h2 * (h1 + h2))) * x[n - 1];
  }
  return dx;
}

}  // namespace knoblab::model
