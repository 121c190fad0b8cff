// Knobs from the thesis, ready to simulate (SI units).
//
// The five mechanical knobs (Table 5), parameters from Table 7 set 1:
//   high-friction, high-inertia, subtle-detents, moderate-detents,
//   non-sine-detents.
// Conversions and corrections:
//  * mN·m, mN·m/(rad/s), mN·m/(rad/s²) → N·m, N·m·s/rad, kg·m² (× 1e-3).
//  * C, B, D are magnitudes (Table 7 prints the negative side with its sign).
//  * Δv is printed "(mNm)" but is a velocity band; read as rad/s (Fig. 35
//    puts the subtle knob's band at ±0.01 rad/s, the Table 7 value).
//  * P: Table 7's P_pos for subtle (0.076) and moderate (0.034) are swapped
//    against Table 5 (30 and 12 clicks/rev) and Table 8; we use the "gold
//    standard" counts: P = 1/30 (subtle), 1/12 (moderate, non-sine).
//  * non-sine-detents: M = −0.0048 is non-physical → 0.034, the same car's
//    volume knob's (lighter, the capture loop hunts inside the play). A = −202 mN·m is
//    beyond the sensor (±180) and the actuator (181 mN·m): capped to 61 mN·m
//    (Table 7 set 2's |A|), the sign moved into the phase (S + π). D = 200
//    mN·m could never be broken away by the 181 mN·m motor: capped to
//    90 mN·m, so D + the peak detent torque stays under both limits. The
//    knob's non-sinusoidal shape comes from Detents harmonics (2nd: skew,
//    3rd: flat, wide detents) and 2.8 mrad of backlash (KnobParams::backlash).
//
// The 7 stimuli of Study 2 (Table 19) and Study 3 (Table 20), ids
// study2-… and study3-…: τ = a1·sin(a2·θ) + b·θ̇ + m·θ̈. The tables say
// "Units in Nm, rad, and s", but the values only fit the haptic knob's limits
// (Table 9: 180 mNm, 45 mNm/(rad/s), 1.5 mNm/(rad/s²)) in mN·m units, so a1
// is mN·m, b mN·m/(rad/s), m mN·m/(rad/s²). Detents: a2 is read as the
// detent period in rad (P = a2/2π), giving 1, 3 and 5 detents per revolution
// for "few", Study 2 "many" and Study 3 "many". Read literally as a spatial
// frequency (P = 1/a2), "many detents" would have fewer detents than "few"
// (2.09 and 1.26 against 6.28 per revolution), which the labels rule out. The knob itself adds the haptic knob's own 0.013
// mN·m/(rad/s²) (§3.3.2) to m, so "not rendered" still has inertia.
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "knoblab/sim/knob.hpp"

namespace knoblab::sim::presets {

struct Preset {
  std::string_view id;
  std::string_view description;  // one line
  KnobParams knob;
};

struct PresetInfo {
  std::string_view id;
  std::string_view description;
};

// Inertia of the Study 2/3 haptic knob's mechanism, motor included (§3.3.2).
inline constexpr double kHapticKnobInertia = 0.013e-3;  // kg·m²

// One column of thesis Table 7 exactly as printed: mN·m, mN·m/(rad/s),
// mN·m/(rad/s²), rad, rad/s, with the printed signs; NaN for a blank cell.
// ci95 is the table's last row, the torque's overall 95% CI (mN·m).
struct Table7Column {
  double M, C_neg, B_neg, C_pos, B_pos, D_neg, D_pos, dv, A, P, S, ci95;
};
// Set 1 or 2 for one of the five thesis knobs; nullptr otherwise.
const Table7Column* table7(std::string_view id, int set);

std::span<const Preset> all();
std::vector<PresetInfo> list();
const Preset* find(std::string_view id);  // nullptr when unknown
std::optional<KnobParams> knob(std::string_view id);

}  // namespace knoblab::sim::presets
