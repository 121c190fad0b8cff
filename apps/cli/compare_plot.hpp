// knoblab compare's plots: the two sides overlaid, as the fit report's
// middle panels draw one — τ_pos against θ and τ_vel against θ̇, each
// capture's raw part (its torque less its model's other parts) as a cloud
// and each model's term as a line. Effects are not drawn (the table lists
// them). PNG and SVG through the fit report's PLplot helpers.
#pragma once

#include <filesystem>
#include <vector>

#include "compare_side.hpp"

namespace knoblab::cli {

// Writes torque_position and torque_velocity (.png, .svg) into `dir`,
// creating it; returns the files. Throws std::runtime_error naming a file
// that cannot be written.
std::vector<std::filesystem::path> write_compare_plots(const std::filesystem::path& dir, const CompareSide& a,
                                                       const CompareSide& b);

}  // namespace knoblab::cli
