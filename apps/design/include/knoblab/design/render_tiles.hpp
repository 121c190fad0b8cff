// A design as hapticd renders it: the arguments of `load_tiles`
// (docs/protocol.md), made of the active lines of the channels that play;
// and such a render model read back into a design.
//
//   position     → position tile {theta_min, theta_max, torque}
//   velocity     → position tile {theta_min, theta_max, torque_of_velocity}
//   acceleration → position tile {theta_min, theta_max, mass}
//   time         → time tile {start, duration, torque, loop + period}
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "knoblab/design/design.hpp"

namespace knoblab::design {

nlohmann::json load_tiles_args(const Design& d);

// One line per channel, each render tile a placed tile whose waveform is the
// curve as played (knots in the channel's own units). Throws
// jsonread::PathError naming the key when `args` is not such a model.
Design design_from_load_tiles(const nlohmann::json& args, const std::string& name);

// The time channel's length: where its last tile ends (s); a looping
// channel repeats after it.
double time_channel_end(const Design& d);

}  // namespace knoblab::design
