#include "knoblab/model/tiles.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::model {
namespace {

// f_pos(s)·θ + f_vel(s)·θ̇ + f_acc(s)·θ̈ for s = θ (Eq. 19) or t (Eq. 20).
template <typename Tile>
double sum_terms(const Tile& tile, double s, const Kinematics<double>& k) noexcept {
  double tau = 0.0;
  if (tile.f_pos) tau += (*tile.f_pos)(s) * k.theta;
  if (tile.f_vel) tau += (*tile.f_vel)(s) * k.omega;
  if (tile.f_acc) tau += (*tile.f_acc)(s) * k.alpha;
  return tau;
}

// Where a natural curve's straight continuation starts, or nothing when x
// is inside its knots (or the curve wraps).
std::optional<double> outside_end(const CubicSpline& f, double x) noexcept {
  if (f.empty() || f.boundary() == SplineBoundary::kPeriodic) return std::nullopt;
  if (x < f.x_min()) return f.x_min();
  if (x > f.x_max()) return f.x_max();
  return std::nullopt;
}

}  // namespace

double evaluate_straight_ends(const CubicSpline& f, double x) noexcept {
  if (const auto end = outside_end(f, x)) return f(*end) + f.derivative(*end) * (x - *end);
  return f(x);
}

double slope_straight_ends(const CubicSpline& f, double x) noexcept {
  return f.derivative(outside_end(f, x).value_or(x));
}

double PositionTile::torque(const Kinematics<double>& k) const noexcept {
  if (!contains(k.theta)) return 0.0;
  double tau = sum_terms(*this, k.theta, k);
  if (torque_of_angle) tau += (*torque_of_angle)(k.theta);
  if (torque_of_velocity) tau += evaluate_straight_ends(*torque_of_velocity, k.omega);
  return tau;
}

double PositionTile::mass_at(double theta) const noexcept {
  return mass && contains(theta) ? (*mass)(theta) : 0.0;
}

double PositionTile::stiffness_at(double theta) const noexcept {
  if (!contains(theta)) return 0.0;
  double k = 0.0;
  if (torque_of_angle) k += torque_of_angle->derivative(theta);
  if (f_pos) k += (*f_pos)(theta) + f_pos->derivative(theta) * theta;  // d(f·θ)/dθ
  return k;
}

double PositionTile::damping_at(double theta) const noexcept {
  return f_vel && contains(theta) ? (*f_vel)(theta) : 0.0;
}

std::pair<double, double> PositionTile::velocity_slope_range(double velocity_limit) const noexcept {
  if (!torque_of_velocity) return {0.0, 0.0};
  const CubicSpline& g = *torque_of_velocity;
  // A cubic's slope is a parabola: its extremes are at the ends of a
  // segment or at its vertex, so knots plus a fine grid find them.
  constexpr int kPoints = 4096;
  const double v = std::abs(velocity_limit);
  double lo = slope_straight_ends(g, -v), hi = lo;
  const auto see = [&](double x) {
    if (x < -v || x > v) return;
    const double s = slope_straight_ends(g, x);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  };
  for (int i = 0; i <= kPoints; ++i) see(-v + 2.0 * v * i / kPoints);
  for (const double x : g.knots()) see(x);
  return {lo, hi};
}

std::optional<double> TimeTile::local_time(double t) const noexcept {
  if (!(duration > 0.0) || t < 0.0) return std::nullopt;
  const double end = start + duration;
  if (loop && t > end) {
    const double every = period > 0.0 ? period : end;
    t = std::fmod(t, every);
  }
  if (t < start || t > end) return std::nullopt;
  return t - start;
}

double TimeTile::torque(double t, const Kinematics<double>& k) const noexcept {
  const std::optional<double> local = local_time(t);
  if (!local) return 0.0;
  double tau = sum_terms(*this, *local, k);
  if (torque_of_time) tau += (*torque_of_time)(*local);
  return tau;
}

double total_torque(std::span<const PositionTile> tiles, const Kinematics<double>& k) noexcept {
  double tau = 0.0;
  for (const PositionTile& tile : tiles) tau += tile.torque(k);
  return tau;
}

double total_torque(std::span<const TimeTile> tiles, double t,
                    const Kinematics<double>& k) noexcept {
  double tau = 0.0;
  for (const TimeTile& tile : tiles) tau += tile.torque(t, k);
  return tau;
}

double total_mass(std::span<const PositionTile> tiles, double theta) noexcept {
  double m = 0.0;
  for (const PositionTile& tile : tiles) m += tile.mass_at(theta);
  return m;
}

}  // namespace knoblab::model
