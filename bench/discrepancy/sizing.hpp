// Sizes for the concealed operator effects (time_delay, saturation,
// hysteresis, backlash), whose setting is an angle, a time or a limit rather
// than a torque amplitude, and for compliance (a stiffness; last below):
// each operator's setting is the one whose signature on the clean knob's
// capture — the operator applied to its prepared motion and
// torque, minus the torque without it — has a given RMS over the rows
// discovery analyses (faster than 2 % of the 95th-percentile speed and than
// the knob's stick band). That puts them on the same footing as the torque
// effects, whose amplitudes are multiples of the clean residual r. Settings
// stay within the range discovery searches (delay ≤ 5 ms, presliding angle
// ≤ 30 mrad, backlash ≤ 16 mrad): past it the benchmark would test the grid's
// reach, not the naming; where the bound holds the signature falls short.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/sim/knob.hpp"

namespace knoblab::bench {

// The rows discovery analyses (docs/discrepancy.md, "How it decides" 2):
// faster than 2 % of the 95th-percentile speed and than the stick band's
// half-width `stick_speed` (rad/s).
std::vector<std::size_t> analysed_rows(const fit::FitData& d, double stick_speed);
// RMS of x over those rows.
double rms_over(const std::vector<double>& x, const std::vector<std::size_t>& rows);

// delay_s: τ(t) − τ(t − δ).
double size_time_delay(const fit::FitData& clean, const sim::KnobParams& knob, double rms);
// limit_Nm: τ − saturate(τ, L).
double size_saturation(const fit::FitData& clean, const sim::KnobParams& knob, double rms);
// presliding_rad: C·z (Dahl) − C·sgn(ω).
double size_hysteresis(const fit::FitData& clean, const sim::KnobParams& knob, double rms);
// width_rad: the knob's position torque at the played-off mechanism; out of
// contact, none of the knob's position torque and friction.
double size_backlash(const fit::FitData& clean, const sim::KnobParams& knob, double rms);

// stiffness_Nm_per_rad of a softer gripper coupling (damping at the
// default's ratio). A softer coupling changes what the rig's position loop
// does (it rings), so no signature on the clean capture predicts its size:
// it is sized on captures simulated with it instead, by the residual it adds
// to the thesis model's fit there, excess(k) = √(rms(k)² − rms_clean²), the
// largest k whose excess reaches `rms` (the stiffest that still shows).
// Softer than kMinCouplingStiffness the loop rings at ≈ 400 Hz into its
// torque limit (moderate-detents at 3 N·m/rad): a broken capture anyone
// would see, not a concealed effect.
inline constexpr double kMinCouplingStiffness = 5.0;
double size_compliance(const std::function<double(double)>& excess, double rms);

}  // namespace knoblab::bench
