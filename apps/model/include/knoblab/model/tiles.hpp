// Haptic Icon Prototyper tiles (thesis Ch. 5, Eq. 19 and 20).
//
// Both equations are implemented literally as printed:
//   position tile  τ = f_pos(θ)·θ + f_vel(θ)·θ̇ + f_acc(θ)·θ̈     (Eq. 19)
//   time tile      τ = f_pos(t)·θ + f_vel(t)·θ̇ + f_acc(t)·θ̈     (Eq. 20)
// so f_pos is a stiffness (N·m/rad), f_vel a damping (N·m·s/rad) and f_acc a
// mass (N·m·s²/rad), and the position term multiplies the absolute θ, not θ
// relative to the tile. Eq. 19's sums over several functions are sums over
// tiles: see total_torque().
//
// Beyond the printed equations, the torque waveforms §5.3.1 sketches ("based
// on the user's hand position, velocity and acceleration"):
//   position tile  τ += torque(θ) + torque_of_velocity(θ̇)
//                  mass(θ) joins the renderer's virtual mass (total_mass())
//   time tile      τ += torque(t)
// torque(θ) is f_pos(θ)·θ written as the torque it gives, so it is defined at
// θ = 0. torque_of_velocity continues along its end slopes beyond its first
// and last knot (a damping line keeps damping at any speed), not along the
// natural spline's end cubics. mass is not rendered by feeding back an
// estimated acceleration (f_acc's way): above roughly the device's own
// inertia that is unstable, while the virtual-mass coupling is not.
// An absent curve contributes nothing. Evaluation never allocates.
#pragma once

#include <optional>
#include <span>
#include <utility>

#include "knoblab/model/spline.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::model {

struct PositionTile {
  std::optional<CubicSpline> f_pos, f_vel, f_acc;  // functions of θ (rad)
  std::optional<CubicSpline> torque_of_angle;      // N·m over θ (rad, absolute); load_tiles' "torque"
  std::optional<CubicSpline> torque_of_velocity;   // N·m over θ̇ (rad/s), straight beyond its ends
  std::optional<CubicSpline> mass;                 // kg·m² over θ (rad), ≥ 0
  // Active on [theta_min, theta_max] (rad); 0 outside. A periodic spline
  // with a range wider than its knots repeats its profile across the range.
  double theta_min = 0.0, theta_max = 0.0;

  bool contains(double theta) const noexcept {
    return theta >= theta_min && theta <= theta_max;
  }
  double torque(const Kinematics<double>& k) const noexcept;  // N·m (mass not included)
  double mass_at(double theta) const noexcept;                 // kg·m², 0 outside

  // The linearised loop's view (render_stability.hpp), 0 outside the span:
  // dτ/dθ of torque(θ) and f_pos(θ)·θ (N·m/rad), and f_vel(θ) (N·m·s/rad).
  double stiffness_at(double theta) const noexcept;
  double damping_at(double theta) const noexcept;
  // Least and greatest slope dτ/dθ̇ of torque_of_velocity for |θ̇| ≤
  // velocity_limit (N·m·s/rad); {0, 0} without one. Scans the curve.
  std::pair<double, double> velocity_slope_range(double velocity_limit) const noexcept;
};

struct TimeTile {
  std::optional<CubicSpline> f_pos, f_vel, f_acc;  // functions of t (s)
  std::optional<CubicSpline> torque_of_time;       // N·m over t (s); load_tiles' "torque"
  // Active for start <= t <= start + duration; its curves run on the
  // tile's own clock, t − start. A prototyper's time line places its tiles
  // one after another with `start`.
  double start = 0.0;     // s
  double duration = 0.0;  // s
  bool loop = false;      // repeat every `period` seconds from t = 0 on
  double period = 0.0;    // s; 0: start + duration (the tile alone repeats)

  // Time inside the tile for t seconds since the tile started, or nothing
  // when the tile is not active.
  std::optional<double> local_time(double t) const noexcept;
  double torque(double t, const Kinematics<double>& k) const noexcept;  // N·m
};

// torque_of_velocity's rule: the spline inside its knots, the tangent line at
// the nearer end outside them (periodic curves wrap as usual).
double evaluate_straight_ends(const CubicSpline& f, double x) noexcept;
double slope_straight_ends(const CubicSpline& f, double x) noexcept;

// Eq. 19/20's sums: the torque of several tiles at once.
double total_torque(std::span<const PositionTile> tiles, const Kinematics<double>& k) noexcept;
double total_torque(std::span<const TimeTile> tiles, double t,
                    const Kinematics<double>& k) noexcept;
// The position tiles' mass at θ (kg·m²), for the renderer's virtual mass.
double total_mass(std::span<const PositionTile> tiles, double theta) noexcept;

}  // namespace knoblab::model
