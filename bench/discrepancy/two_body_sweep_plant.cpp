// The effect-size sweep on the two-body rig (two_body_plant.hpp): the same
// knobs by their parameter values, each effect put in by the rig's own
// physics. The rig: a 2000 N·m/rad gripper at a damping ratio of 0.1
// against the knob, 0.1 mN·m of torque noise, the 640 000-count encoder;
// α from the encoder, or from a knob-side accelerometer.
#include <algorithm>

#include "knoblab/model/effect_table.hpp"
#include "sweep_plant.hpp"
#include "two_body_plant.hpp"

namespace knoblab::bench {

namespace {

constexpr double kGripperStiffness = 2000.0;  // N·m/rad
constexpr double kGripperZeta = 0.1;
constexpr double kTorqueNoise = 0.1e-3;       // N·m RMS
// The thesis rig's accelerometer: 4 % of its ±2 g full scale at 15 mm,
// peak to peak (§2.1.2.3), as an RMS.
constexpr double kAccelerometerNoise = 8.7;   // rad/s²
// The knob's own Stribeck speed: half its Karnopp band, so that the static
// excess is gone by the band's edge, where Eq. 7 stops holding the knob.
constexpr double kStribeckPerBand = 0.5;
constexpr double kNoBandStribeck = 0.005;     // rad/s, a knob without a band

std::string num(double x) { return model::shortest_number(x); }

// The knob's parameter values on the two-body rig: Karnopp's static level
// D becomes the breakaway of a Stribeck curve (ΔC = D − C).
TwoBodyKnob two_body_knob(const sim::KnobParams& p) {
  TwoBodyKnob k;
  k.inertia = p.inertia.M;
  k.coulomb_pos = p.friction.C_pos;
  k.coulomb_neg = p.friction.C_neg;
  k.viscous_pos = p.friction.B_pos;
  k.viscous_neg = p.friction.B_neg;
  const double coulomb = 0.5 * (p.friction.C_pos + p.friction.C_neg);
  const double stat = 0.5 * (p.stick.D_pos + p.stick.D_neg);
  k.static_excess = std::max(0.0, stat - coulomb);
  k.stribeck_speed = p.stick.dv > 0.0 ? kStribeckPerBand * p.stick.dv : kNoBandStribeck;
  k.detent_amplitude = p.detents.A;
  k.detent_period = p.detents.P;
  k.detent_phase = p.detents.S;
  for (std::size_t n = 2; n <= 4 && n <= p.detents.harmonics; ++n) {
    k.detent_sin[n - 2] = p.detents.a[n];
    k.detent_cos[n - 2] = p.detents.b[n];
  }
  k.spring = p.spring.K;
  k.spring_cubic = p.spring.K3;
  return k;
}

class TwoBodySweepPlant final : public SweepPlant {
 public:
  explicit TwoBodySweepPlant(bool accelerometer) : accelerometer_(accelerometer) {}
  std::string name() const override { return accelerometer_ ? "two-body (accelerometer)" : "two-body"; }

  std::vector<SweepEffect> effects() const override {
    return {
        {"gravity", "amplitude_Nm", 1e-7, 0.05, 1e-3, true, true},
        {"spring", "stiffness_Nm_per_rad", 1e-7, 0.1, 1e-3, true, true},
        {"periodic_torque", "amplitude_Nm", 1e-7, 0.05, 1e-3, true, true},
        {"detent_shape", "a2_Nm (b3_Nm = a2_Nm/2)", 1e-7, 0.05, 1e-3, true, true},
        // The knob's own Stribeck curve, its speed widened (× its own, Δv/2):
        // ΔC = D − C stays. At ×1 the knob is the clean one.
        {"stribeck", "× the knob's own stribeck_velocity_rad_s", 1.0, 400.0, 10.0, false, true},
        {"nonlinear_damping", "drag N·m·s²/rad²", 1e-9, 0.01, 1e-4, false, true},
        {"endstop", "stiffness_Nm_per_rad (stops at ±0.9 rad)", 1e-5, 10.0, 0.05, false, true},
        {"backlash", "play_rad (in the coupling)", 1e-5, 0.02, 2e-3, false, true},
        {"compliance", "stiffness_Nm_per_rad (ζ 0.1)", 2.0, kGripperStiffness, 100.0, false, false},
    };
  }

  std::string describe(const SweepEffect& e, double s) const override {
    if (e.id == "gravity") return "gravity:amplitude_Nm=" + num(s) + ",phase_rad=0.5";
    if (e.id == "spring") return "spring:stiffness_Nm_per_rad=" + num(s);
    if (e.id == "periodic_torque")
      return "periodic_torque:amplitude_Nm=" + num(s) + ",period_rad=" + num(kCoggingPeriodRad) + ",phase_rad=0.3";
    if (e.id == "detent_shape") return "detent_shape:a2_Nm=" + num(s) + ",b3_Nm=" + num(s / 2);
    if (e.id == "stribeck") return "stribeck: the knob's own curve, stribeck_velocity_rad_s ×" + num(s);
    if (e.id == "nonlinear_damping") return "nonlinear_damping:coefficient=" + num(s) + ",exponent=2";
    if (e.id == "endstop") return "endstop:position_rad=0.9,stiffness_Nm_per_rad=" + num(s);
    if (e.id == "backlash") return "backlash:width_rad=" + num(s) + " (coupling play)";
    return "compliance:stiffness_Nm_per_rad=" + num(s) + ",zeta=" + num(kGripperZeta);
  }

  interchange::Capture capture(const SweepKnob& knob, const SweepEffect* effect, double s,
                               std::uint64_t seed) const override {
    TwoBodyConfig c;
    c.knob_name = knob.name;
    c.knob = two_body_knob(knob.params);
    c.coupling.stiffness = kGripperStiffness;
    c.camera.torque_noise_rms = kTorqueNoise;
    c.camera.seed = seed;
    c.camera.accelerometer = accelerometer_;
    c.camera.accelerometer_noise_rms = kAccelerometerNoise;
    c.seconds = 8.0;
    const std::string id = effect ? effect->id : "";
    TwoBodyKnob& k = c.knob;
    if (id == "gravity") {
      k.gravity = s;
      k.gravity_phase = 0.5;
    } else if (id == "spring") {
      k.spring += s;
    } else if (id == "periodic_torque") {
      k.periodic_amplitude = s;
      k.periodic_period_rad = kCoggingPeriodRad;
      k.periodic_phase = 0.3;
    } else if (id == "detent_shape") {
      k.detent_sin[0] += s;
      k.detent_cos[1] += s / 2;
    } else if (id == "stribeck") {
      k.stribeck_speed *= s;
    } else if (id == "nonlinear_damping") {
      k.drag = s;
    } else if (id == "endstop") {
      k.endstop_angle = 0.9;
      k.endstop_stiffness = s;
    } else if (id == "backlash") {
      c.coupling.play = s;
    } else if (id == "compliance") {
      c.coupling.stiffness = s;
    }
    c.coupling.damping = Coupling::damping_for(kGripperZeta, c.coupling.stiffness, k.inertia);
    TwoBodyRun run = run_two_body(c);
    if (effect) run.capture.metadata.emplace_back("effects", describe(*effect, s));
    return std::move(run.capture);
  }

  double torque_noise() const override { return kTorqueNoise; }

 private:
  bool accelerometer_;
};

}  // namespace

std::unique_ptr<SweepPlant> two_body_sweep_plant(bool accelerometer) {
  return std::make_unique<TwoBodySweepPlant>(accelerometer);
}

}  // namespace knoblab::bench
