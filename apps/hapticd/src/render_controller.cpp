#include "knoblab/hapticd/render_controller.hpp"

#include <algorithm>
#include <cmath>

#include "knoblab/model/models.hpp"

namespace knoblab::hapticd {

namespace {
double frequency_of(const RenderParams& p) { return p.P_pos > 0.0 ? 1.0 / p.P_pos : 0.0; }
}  // namespace

RenderController::RenderController(const RenderConfig& cfg)
    : cfg_(cfg),
      dt_(1.0 / cfg.rate_hz),
      ramp_cycles_(static_cast<int>(std::lround(kParamRampSeconds * cfg.rate_hz))) {}

void RenderController::set_params(const RenderParams& p, bool immediately) {
  target_ = p;
  const int n = immediately ? 0 : ramp_cycles_;
  M_.retarget(p.M_acc, n);
  B_.retarget(p.B_vel, n);
  A_.retarget(p.A_pos, n);
  f_.retarget(frequency_of(p), n);
  if (immediately) {
    effects_ = p.effects;
    effects_pending_ = false;
    effects_gain_.set(1.0);
  } else if (p.effects != (effects_pending_ ? next_effects_ : effects_)) {
    next_effects_ = p.effects;
    effects_pending_ = true;
    effects_gain_.retarget(0.0, n / 2);
  }
}

void RenderController::reset() {
  acc_box_.reset();
  alpha_box_.reset();
  started_ = false;
  cycle_ = 0;
  if (effects_pending_) {  // nothing is felt yet: no fade
    effects_ = next_effects_;
    effects_pending_ = false;
  }
  effects_gain_.set(1.0);
  tiles_start_t_ = 0.0;  // time tiles start over with the render clock
  if (tiles_.has_previous() && tiles_.release_previous()) previous_tiles_ = nullptr;  // nothing felt yet: no fade
  tiles_fade_.set(1.0);
}

model::LoopDynamics RenderController::loop_dynamics(double rate_hz) {
  const capture::SensorConfig sensors;  // the front end's render velocity filter
  model::LoopDynamics d;
  d.rate_hz = rate_hz;
  d.velocity_filter_order = sensors.velocity_filter_order;
  d.velocity_cutoff_hz = std::min(sensors.render_velocity_cutoff_hz, 0.2 * rate_hz);
  return d;
}

void RenderController::take_tiles() {
  // The fade runs whatever the mode, so a set loaded while idle is whole
  // by the time it is felt.
  if (tiles_.has_previous() && tiles_fade_.step() >= 1.0 && tiles_.release_previous()) previous_tiles_ = nullptr;
  if (!tiles_.take_keeping_previous()) return;
  previous_tiles_ = active_tiles_;
  previous_start_t_ = tiles_start_t_;
  active_tiles_ = tiles_.held();
  tiles_start_t_ = static_cast<double>(cycle_) * dt_;
  // This cycle still feels the old set whole; the new one grows from here.
  tiles_fade_.set(0.0);
  tiles_fade_.retarget(1.0, std::max(ramp_cycles_, 1));
}

void RenderController::update(const capture::SensorReading& in, capture::DaqOutputs& out,
                              capture::Sample& s) {
  s.t = static_cast<double>(cycle_++) * dt_;
  s.theta = in.theta;
  s.omega = in.omega_render;
  s.torque = in.torque;
  if (!started_) {  // the virtual mass starts where and as the knob moves
    vm_.reset(s.theta, s.omega);
    prev_omega_ = s.omega;
    started_ = true;
  }

  const double B = B_.step(), A = A_.step(), f = f_.step();
  // Tiles' mass joins the virtual mass (its coupling renders any mass
  // stably; feeding back an estimated θ̈ would not), cross-faded like their torque.
  const double w_new = tiles_.has_previous() ? tiles_fade_.value() : 1.0;
  const double w_old = tiles_.has_previous() ? 1.0 - w_new : 0.0;
  double M = M_.step();
  if (active_tiles_) M += w_new * model::total_mass(active_tiles_->position, s.theta);
  if (previous_tiles_) M += w_old * model::total_mass(previous_tiles_->position, s.theta);
  const double g = effects_gain_.step();
  if (effects_pending_ && g == 0.0) {  // faded out: the new set fades in
    effects_ = next_effects_;
    effects_pending_ = false;
    effects_gain_.retarget(1.0, ramp_cycles_ / 2);
  }

  // Inertia: virtual-mass coupling, box-filtered; its mass acceleration is
  // what the knob "has", so it is also the recorded α in render mode.
  const double tau_acc = acc_box_.process(vm_.update(M, target_.K_vm, target_.B_vm, s.theta, s.omega, dt_));
  s.alpha = M > 0.0 ? tau_acc / M : 0.0;

  // Damping, detents, the stick band and the effects: the model core's terms.
  model::RenderModel<double> m;
  m.B_vel = B;
  m.detents.A = A;
  m.detents.P = f > 0.0 ? 1.0 / f : 1.0;
  if (!(f > 0.0)) m.detents.A = 0.0;
  m.stick_enabled = target_.stick;
  m.stick = {target_.dv, target_.D_neg, target_.D_pos};
  m.effects = g == 1.0 ? effects_ : effects_.scaled(g);
  if (f > 0.0) m.effects.shape_detents(m.detents);  // harmonics of detents there are
  const model::Kinematics<double> k{s.theta, s.omega, 0.0};  // M = 0: inertia is the virtual mass
  double tau = m.torque(k, s.torque - tau_acc) + tau_acc;

  // Prototyper tiles: acceleration from the filtered velocity, box-smoothed.
  const double alpha_est = alpha_box_.process((s.omega - prev_omega_) / dt_);
  prev_omega_ = s.omega;
  const model::Kinematics<double> kt{s.theta, s.omega, alpha_est};
  if (const TileSet* tiles = active_tiles_)
    tau += w_new * (model::total_torque(tiles->position, kt) +
                    model::total_torque(tiles->time, s.t - tiles_start_t_, kt));
  if (const TileSet* tiles = previous_tiles_)
    tau += w_old * (model::total_torque(tiles->position, kt) +
                    model::total_torque(tiles->time, s.t - previous_start_t_, kt));

  // The knob resists with τ, so the motor pushes with −τ.
  s.command = -tau / cfg_.torque_per_volt;
  out.motor_command_V = s.command;
  out.amp_enable = true;
}

}  // namespace knoblab::hapticd
