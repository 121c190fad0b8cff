#include "knoblab/model/tiles.hpp"

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

}  // namespace

double PositionTile::torque(const Kinematics<double>& k) const noexcept {
  return contains(k.theta) ? sum_terms(*this, k.theta, k) : 0.0;
}

std::optional<double> TimeTile::local_time(double t) const noexcept {
  if (!(duration > 0.0) || t < 0.0) return std::nullopt;
  if (t <= duration) return t;
  if (!loop) return std::nullopt;
  return std::fmod(t, duration);
}

double TimeTile::torque(double t, const Kinematics<double>& k) const noexcept {
  const std::optional<double> local = local_time(t);
  return local ? sum_terms(*this, *local, k) : 0.0;
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

}  // namespace knoblab::model
