// A design as QML reads it: plain lists and maps of SI numbers (the screen
// converts to degrees and mN·m at its edge), rebuilt whole after each edit —
// designs are small.
#pragma once

#include <QVariantList>
#include <QVariantMap>

#include "knoblab/design/design.hpp"

namespace knoblab::ui {

// [{x, y}] of the control points.
QVariantList points_variant(const design::Waveform& w);

// The curve the renderer plays, sampled at n + 1 x from `from` to `to`
// ([{x, y}]); beyond the points it goes on along the end slopes.
QVariantList curve_variant(const design::Waveform& w, double from, double to, int n);

// The curve's shape for a thumbnail: [{x, y}] with x in 0…1 over its points
// and y in −1…1 (divided by the largest |y|; flat when all are 0).
QVariantList thumb_variant(const design::Waveform& w);

// [{name, tiles: [{name, drawnFor, peak, thumb}]}]; peak is the largest |y| (SI).
QVariantList palette_variant(const design::Design& d);

// One entry per channel, in kChannels order: {name, play, lines: [{active,
// tiles: [{name, drawnFor, from, to, peak, thumb}]}]}.
QVariantList channels_variant(const design::Design& d);

// "position" → Channel::Position; throws std::invalid_argument otherwise.
design::Channel channel_of(const QString& name);

}  // namespace knoblab::ui
