// The effect-size sweep on knoblab's simulator: `knoblab simulate` with the
// effect in --effects (the Table 3 sweep through the PID and HapticCore).
#include <cstdio>

#include "knoblab/model/effect_table.hpp"
#include "knoblab/sim/torque_sensor.hpp"
#include "simulation.hpp"
#include "sweep_plant.hpp"

namespace knoblab::bench {

namespace {

std::string num(double x) { return model::shortest_number(x); }

class SimSweepPlant final : public SweepPlant {
 public:
  std::string name() const override { return "sim"; }

  std::vector<SweepEffect> effects() const override {
    return {
        {"gravity", "amplitude_Nm", 1e-7, 0.05, 1e-3, true, true},
        {"spring", "stiffness_Nm_per_rad", 1e-7, 0.1, 1e-3, true, true},
        {"periodic_torque", "amplitude_Nm", 1e-7, 0.05, 1e-3, true, true},
        {"detent_shape", "a2_Nm (b3_Nm = a2_Nm/2)", 1e-7, 0.05, 1e-3, true, true},
        {"stribeck", "static_excess_Nm (v_s 0.5 rad/s)", 1e-7, 0.1, 2e-3, false, true},
        {"nonlinear_damping", "coefficient (exponent 2)", 1e-9, 0.01, 1e-4, false, true},
        {"endstop", "stiffness_Nm_per_rad (stops at ±0.9 rad)", 1e-5, 10.0, 0.05, false, true},
        {"backlash", "width_rad", 1e-5, 0.02, 2e-3, false, true},
        // The rig's own gripper is 100 N·m/rad; softer than 5 the loop rings
        // into its torque limit (sizing.hpp).
        {"compliance", "stiffness_Nm_per_rad", 5.0, 100.0, 30.0, false, false},
    };
  }

  std::string describe(const SweepEffect& e, double s) const override {
    if (e.id == "gravity") return "gravity:amplitude_Nm=" + num(s) + ",phase_rad=0.5";
    if (e.id == "spring") return "spring:stiffness_Nm_per_rad=" + num(s);
    if (e.id == "periodic_torque")
      return "periodic_torque:amplitude_Nm=" + num(s) + ",period_rad=" + num(kCoggingPeriodRad) + ",phase_rad=0.3";
    if (e.id == "detent_shape") return "detent_shape:a2_Nm=" + num(s) + ",b3_Nm=" + num(s / 2);
    if (e.id == "stribeck") return "stribeck:static_excess_Nm=" + num(s) + ",stribeck_velocity_rad_s=0.5";
    if (e.id == "nonlinear_damping") return "nonlinear_damping:coefficient=" + num(s) + ",exponent=2";
    if (e.id == "endstop") return "endstop:position_rad=0.9,stiffness_Nm_per_rad=" + num(s);
    if (e.id == "backlash") return "backlash:width_rad=" + num(s);
    return "compliance:stiffness_Nm_per_rad=" + num(s);
  }

  interchange::Capture capture(const SweepKnob& knob, const SweepEffect* effect, double setting,
                               std::uint64_t seed) const override {
    cli::SimulationRequest req;
    req.knob_name = knob.name;
    req.knob = knob.params;
    req.seconds = 8.0;
    req.rate_hz = 5000.0;
    req.seed = seed;
    if (effect) req.effects = model::parse_effect_specs(describe(*effect, setting));
    return cli::simulate(req, nullptr).capture;
  }

  // The torque sensor's; the accelerometer's noise comes on top, through M.
  double torque_noise() const override { return sim::TorqueSensorParams{}.noise_sigma; }
};

}  // namespace

std::unique_ptr<SweepPlant> sim_sweep_plant() { return std::make_unique<SimSweepPlant>(); }

}  // namespace knoblab::bench
