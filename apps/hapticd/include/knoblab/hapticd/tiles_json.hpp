// load_tiles' arguments (docs/protocol.md §7) turned into a
// TileSet the renderer can run, or the reason it must not: curves that are
// not functions (knots not increasing, x and y of different lengths, a
// periodic curve whose ends differ), a tile's range empty, damping or mass
// below zero anywhere on its curve (it would feed energy into the knob), or a
// position tile whose spring torque alone exceeds the device's torque limit;
// a torque curve past the torque limit (torque_of_velocity at any speed up
// to the velocity limit), a mass below zero or above kMaxTileMass; and tiles
// whose local stiffness and damping (overlapping tiles added up) lie outside
// what the loop renders stably (model/render_stability.hpp, for `loop`).
// The protocol schema has already checked shapes, types and ranges.
#pragma once

#include <memory>
#include <variant>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/hapticd/render_params.hpp"
#include "knoblab/hapticd/supervisor.hpp"
#include "knoblab/hapticd/tile_set.hpp"
#include "knoblab/model/render_stability.hpp"

namespace knoblab::hapticd {

// The most mass tiles may add to the virtual mass: the haptic knob's
// rendering limit, thesis Table 9 (1.5 mN·m/(rad/s²)). hapticd has no M_acc
// limit of its own beyond the protocol's sanity bound.
inline constexpr double kMaxTileMass = 1.5e-3;  // kg·m²

std::variant<std::unique_ptr<TileSet>, ParamProblem> tiles_from_json(const nlohmann::json& args,
                                                                     const SafetyLimits& limits,
                                                                     const model::LoopDynamics& loop = {});

}  // namespace knoblab::hapticd
