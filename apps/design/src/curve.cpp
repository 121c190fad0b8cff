#include "knoblab/design/curve.hpp"

#include <cmath>
#include <vector>

namespace knoblab::design {

std::string waveform_problem(const Waveform& w) {
  if (w.points.size() < 2) return "needs at least 2 points";
  for (const Point& p : w.points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return "has a point that is not a number";
  for (std::size_t i = 1; i < w.points.size(); ++i)
    if (!(w.points[i].x > w.points[i - 1].x)) return "must have its points left to right, each x after the last";
  if (w.periodic && w.points.front().y != w.points.back().y)
    return "repeats, so its first and last points must be equally high";
  return {};
}

model::CubicSpline spline_of(const Waveform& w) {
  std::vector<double> x, y;
  x.reserve(w.points.size());
  y.reserve(w.points.size());
  for (const Point& p : w.points) {
    x.push_back(p.x);
    y.push_back(p.y);
  }
  return model::CubicSpline(x, y, w.periodic ? model::SplineBoundary::kPeriodic : model::SplineBoundary::kNatural);
}

double value_at(const model::CubicSpline& s, double x) {
  if (s.empty()) return 0.0;
  if (s.boundary() == model::SplineBoundary::kPeriodic) return s(x);
  if (x < s.x_min()) return s(s.x_min()) + s.derivative(s.x_min()) * (x - s.x_min());
  if (x > s.x_max()) return s(s.x_max()) + s.derivative(s.x_max()) * (x - s.x_max());
  return s(x);
}

Waveform placed_waveform(const PlacedTile& p, Channel c) {
  Waveform w = p.tile.waveform;
  if (!stretched(c) || w.points.size() < 2) return w;
  const double x0 = w.x_min(), x1 = w.x_max();
  const double scale = (p.to - p.from) / (x1 - x0);
  for (Point& q : w.points) q.x = p.from + (q.x - x0) * scale;
  // The ends land exactly on the span, whatever the rounding.
  w.points.front().x = p.from;
  w.points.back().x = p.to;
  return w;
}

}  // namespace knoblab::design
