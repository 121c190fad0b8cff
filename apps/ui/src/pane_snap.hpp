// Where a tile lands in the tile pane when a finger lets go of it. A finger
// cannot hit an exact angle, but tiles are meant to abut (a wall starts where
// the detents end, Fig. 70), so an end that lands near another tile's end
// snaps onto it exactly — the same double, not one a pixel away — and a
// design built by touch is the design built by numbers.
#pragma once

#include <optional>
#include <vector>

#include "knoblab/design/design.hpp"

namespace knoblab::ui {

struct PaneSpan {
  double from = 0.0, to = 0.0;
};

// A tile of `length` whose start landed at `from`: if its start or its end
// is within `tolerance` of one of `edges`, the nearer one snaps there (and
// the other end follows: from = edge − length or to = edge + length);
// otherwise it stays where it landed.
PaneSpan snap_span(double from, double length, const std::vector<double>& edges, double tolerance);

// One end dragged to `at`: the nearest edge within `tolerance`, else `at`.
double snap_edge(double at, const std::vector<double>& edges, double tolerance);

// A velocity tile's span says only where its curve acts (its waveform is
// over θ̇, not θ): dropped at `at`, it fills the gap between the nearest
// edges either side, so damping dropped between two walls acts exactly
// between them. A side with no edge ends `fallback` / 2 from `at`.
PaneSpan fill_gap(double at, const std::vector<double>& edges, double fallback);

// The ends of every placed tile sharing an axis with channel `c` — the θ
// channels (position, velocity, acceleration) share one, time has its own;
// `skip`, when given, is the tile being moved.
std::vector<double> pane_edges(const design::Design& d, design::Channel c,
                               std::optional<std::pair<std::size_t, std::size_t>> skip = std::nullopt);

}  // namespace knoblab::ui
