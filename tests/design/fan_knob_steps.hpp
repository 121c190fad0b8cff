// The thesis' worked example (§5.3, Fig. 70), built the way a designer does
// it, from the templates through edits: the four-setting fan knob — detents
// at Off, Lo, Med and Hi (−45°, −15°, 15°, 45°: θ = 0 is the middle of the
// travel, so its ends are symmetric), walls beyond Off and Hi, soft
// damping between them and four times stronger beyond, a constant mass.
// examples/designs/fan-knob.json is what this makes (a test keeps them equal).
#pragma once

#include <cstddef>
#include <numbers>

#include "knoblab/design/edits.hpp"
#include "knoblab/design/history.hpp"
#include "knoblab/design/templates.hpp"

namespace knoblab::design::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;
inline constexpr double kDetentsFrom = -60 * kDeg, kDetentsTo = 60 * kDeg;  // four detents, Off … Hi
inline constexpr double kWall = 0.6;                                      // rad, each wall tile's length
inline constexpr double kRangeFrom = kDetentsFrom - kWall, kRangeTo = kDetentsTo + kWall;

inline std::size_t template_index(const Design& d, const char* name) {
  const auto& tiles = d.palette.at(0).tiles;
  for (std::size_t i = 0; i < tiles.size(); ++i)
    if (tiles[i].name == name) return i;
  throw EditError(std::string("no template ") + name);
}

// Every step through `h`, so each is one undoable edit.
inline void build_fan_knob(History& h) {
  h.apply("new design", [](Design& d) { d = new_design("fan knob"); });
  h.apply("added tab", [](Design& d) { add_tab(d, "Fan knob"); });
  // Four clicks out of the detent series: 15°…135° of it holds the rests at
  // 30°, 60°, 90° and 120°, and starts and ends at zero torque; placed on
  // −60°…60° they rest at −45°, −15°, 15° and 45°.
  h.apply("detents into the editor", [](Design& d) { edit_tile(d, 0, template_index(d, "detent series")); });
  h.apply("made a tile", [](Design& d) { add_tile(d, 1, tile_from_selection(d, {15 * kDeg, 135 * kDeg}, "four clicks")); });
  h.apply("placed", [](Design& d) {
    place_tile(d, Channel::Position, 0, d.palette[0].tiles[template_index(d, "wall, anticlockwise end")],
               kDetentsFrom - kWall, kDetentsFrom);
  });
  h.apply("placed", [](Design& d) {
    place_tile(d, Channel::Position, 0, d.palette[1].tiles[0], kDetentsFrom, kDetentsTo);
  });
  h.apply("placed", [](Design& d) {
    place_tile(d, Channel::Position, 0, d.palette[0].tiles[template_index(d, "wall, clockwise end")], kDetentsTo,
               kDetentsTo + kWall);
  });
  // Damping: the template between Off and Hi; four times as much beyond.
  h.apply("placed", [](Design& d) {
    place_tile(d, Channel::Velocity, 0, d.palette[0].tiles[template_index(d, "constant damping")], kDetentsFrom,
               kDetentsTo);
  });
  h.apply("damping into the editor", [](Design& d) { edit_tile(d, 0, template_index(d, "constant damping")); });
  h.apply("scaled", [](Design& d) { scale_selection(d, {-100, 100}, Mirror::Horizontal, 0.0, 4.0); });
  h.apply("made a tile", [](Design& d) { add_tile(d, 1, tile_from_selection(d, {-100, 100}, "strong damping")); });
  h.apply("placed", [](Design& d) {
    place_tile(d, Channel::Velocity, 0, d.palette[1].tiles[1], kDetentsFrom - kWall, kDetentsFrom);
  });
  h.apply("placed", [](Design& d) {
    place_tile(d, Channel::Velocity, 0, d.palette[1].tiles[1], kDetentsTo, kDetentsTo + kWall);
  });
  h.apply("placed", [](Design& d) {
    place_tile(d, Channel::Acceleration, 0, d.palette[0].tiles[template_index(d, "constant mass")], kRangeFrom,
               kRangeTo);
  });
}

inline Design fan_knob() {
  History h;
  build_fan_knob(h);
  return h.design();
}

}  // namespace knoblab::design::testing
