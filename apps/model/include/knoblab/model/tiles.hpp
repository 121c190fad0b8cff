// Haptic Icon Prototyper tiles (thesis Ch. 5, Eq. 19 and 20).
//
// Both equations are implemented literally as printed:
//   position tile  τ = f_pos(θ)·θ + f_vel(θ)·θ̇ + f_acc(θ)·θ̈     (Eq. 19)
//   time tile      τ = f_pos(t)·θ + f_vel(t)·θ̇ + f_acc(t)·θ̈     (Eq. 20)
// so f_pos is a stiffness (N·m/rad), f_vel a damping (N·m·s/rad) and f_acc a
// mass (N·m·s²/rad), and the position term multiplies the absolute θ, not θ
// relative to the tile. A torque-profile tile τ = g(θ) is therefore f_pos =
// g(θ)/θ, or better, expressed through another term. Eq. 19's sums over
// several functions are sums over tiles: see total_torque().
// An absent f contributes nothing. Evaluation never allocates.
#pragma once

#include <optional>
#include <span>

#include "knoblab/model/spline.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::model {

struct PositionTile {
  std::optional<CubicSpline> f_pos, f_vel, f_acc;  // functions of θ (rad)
  // Active on [theta_min, theta_max] (rad); 0 outside. A periodic spline
  // with a range wider than its knots repeats its profile across the range.
  double theta_min = 0.0, theta_max = 0.0;

  bool contains(double theta) const noexcept {
    return theta >= theta_min && theta <= theta_max;
  }
  double torque(const Kinematics<double>& k) const noexcept;  // N·m
};

struct TimeTile {
  std::optional<CubicSpline> f_pos, f_vel, f_acc;  // functions of t (s)
  double duration = 0.0;  // s; the tile is active for 0 <= t <= duration
  bool loop = false;      // repeat every `duration` seconds from t = 0 on

  // Time inside the tile for t seconds since the tile started, or nothing
  // when the tile is not active.
  std::optional<double> local_time(double t) const noexcept;
  double torque(double t, const Kinematics<double>& k) const noexcept;  // N·m
};

// Eq. 19/20's sums: the torque of several tiles at once.
double total_torque(std::span<const PositionTile> tiles, const Kinematics<double>& k) noexcept;
double total_torque(std::span<const TimeTile> tiles, double t,
                    const Kinematics<double>& k) noexcept;

}  // namespace knoblab::model
