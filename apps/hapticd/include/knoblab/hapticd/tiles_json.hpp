// load_tiles' arguments (docs/protocol.md §7) turned into a
// TileSet the renderer can run, or the reason it must not: curves that are
// not functions (knots not increasing, x and y of different lengths, a
// periodic curve whose ends differ), a tile's range empty, damping or mass
// below zero anywhere on its curve (it would feed energy into the knob), or a
// position tile whose spring torque alone exceeds the device's torque limit.
// The protocol schema has already checked shapes, types and ranges.
#pragma once

#include <memory>
#include <variant>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/hapticd/render_params.hpp"
#include "knoblab/hapticd/supervisor.hpp"
#include "knoblab/hapticd/tile_set.hpp"

namespace knoblab::hapticd {

std::variant<std::unique_ptr<TileSet>, ParamProblem> tiles_from_json(const nlohmann::json& args,
                                                                     const SafetyLimits& limits);

}  // namespace knoblab::hapticd
