// The palette's template tiles (§5.3.1: ramp, detent series, walls,
// constant damping, Stribeck friction, constant mass), in SI. Their sizes
// are a starting point a designer drags and scales, each well inside the
// haptic knob's continuous limits (thesis Table 9).
#pragma once

#include "knoblab/design/design.hpp"

namespace knoblab::design {

inline constexpr const char* kTemplatesTab = "Templates";

Tile detent_series();      // 12 per revolution, ±10 mN·m, over one revolution
Tile ramp();               // 0 → 50 mN·m over 0.5 rad
Tile wall_clockwise();     // rises to 120 mN·m in 0.15 rad, then holds: the end of a clockwise range
Tile wall_anticlockwise(); // its mirror image: the end of an anticlockwise range
Tile constant_damping();   // 0.5 mN·m/(rad/s), over ±20 rad/s
Tile stribeck_curve();     // friction over velocity: 5 mN·m breakaway falling to 3 mN·m, then viscous
Tile constant_mass();      // 0.1 mN·m/(rad/s²)

PaletteTab template_tab();       // all of the above
Design new_design(const std::string& name);  // an empty design with the templates tab

}  // namespace knoblab::design
