// A waveform as the curve it stands for: the model core's cubic spline
// through its points (the one the renderer plays), and where a placed tile's
// points land in its channel.
#pragma once

#include <string>

#include "knoblab/design/design.hpp"
#include "knoblab/model/spline.hpp"

namespace knoblab::design {

// Position, acceleration and time tiles stretch their waveform onto their
// span; a velocity tile's waveform is over θ̇, whatever its span.
inline bool stretched(Channel c) { return c != Channel::Velocity; }

// "" when the points make a curve the renderer can play; otherwise why not,
// as a sentence ending "…" that follows "The tile " or "The waveform ".
std::string waveform_problem(const Waveform& w);

// Throws std::invalid_argument when the points are not a function (fewer
// than 2, x not strictly increasing, a periodic curve with unequal ends).
model::CubicSpline spline_of(const Waveform& w);

// The curve at x; beyond its ends it goes on along the end slopes, as the
// renderer extends a velocity tile (a damping line keeps damping).
double value_at(const model::CubicSpline& s, double x);

// The placed tile's waveform in its channel's coordinates: x mapped onto
// [from, to] when the channel stretches, as it is otherwise.
Waveform placed_waveform(const PlacedTile& p, Channel c);

}  // namespace knoblab::design
