// knoblab compare's plots: the two sides overlaid, as the fit report's
// middle panels draw one — τ_pos against θ and τ_vel against θ̇, each
// capture's raw part (its torque less its model's other parts) as a cloud
// and each model's term as a line. Effects are not drawn (the table lists
// them). Drawn by the plot module both reports use (docs/figures.md).
#pragma once

#include <filesystem>
#include <vector>

#include "compare_side.hpp"
#include "knoblab/fit/plot/figure_options.hpp"

namespace knoblab::cli {

// Writes torque_position and torque_velocity (the formats asked for, and
// each one's data as CSV) into `dir`, creating it; returns the files. Throws
// std::runtime_error naming a file that cannot be written.
std::vector<std::filesystem::path> write_compare_plots(const std::filesystem::path& dir, const CompareSide& a,
                                                       const CompareSide& b,
                                                       const fit::plot::FigureOptions& options);

}  // namespace knoblab::cli
