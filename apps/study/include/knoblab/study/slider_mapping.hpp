// Where a matching slider's knob sits (its position, 0 at the bottom, 1 at
// the top) and the value it sets (SI), by Stevens' power law (thesis
// §3.4.3.3: a linear slider in engineering units need not feel linear).
// The perceived magnitude of a stimulus φ grows as ψ ∝ φ^β, so a slider
// whose position is proportional to ψ moves its value as
//
//   value = min + (max − min)·position^(1/β)     position = ((value − min)/(max − min))^β
//
// with φ counted from the slider's bottom (min; 0 in the thesis' sliders).
// β = 1 is the linear slider; β < 1 gives more of the slider's travel to the
// low values (where a compressive sense tells small differences apart),
// β > 1 to the high ones. The one definition: the participant view maps its
// slider positions through it; the runner and the store see only values.
#pragma once

#include "knoblab/study/protocol.hpp"

namespace knoblab::study {

// `position` is clamped to [0, 1]; the value is in [min, max].
// Throws std::invalid_argument for a position that is not finite or a slider
// whose range or exponent is not valid (max ≤ min, β ≤ 0 or not finite).
double slider_value(const Slider& slider, double position);

// The inverse: `value` clamped to [min, max], the position in [0, 1].
// Throws std::invalid_argument as slider_value.
double slider_position(const Slider& slider, double value);

}  // namespace knoblab::study
