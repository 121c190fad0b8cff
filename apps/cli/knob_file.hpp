// Knob parameters from a JSON file, so a fitted or hand-designed knob can be
// simulated. The format is the fit's output (SI units, thesis Eq. 6 names):
//   {"model": "thesis6",
//    "params": {"M_acc": …, "C_vel_neg": …, "B_vel_neg": …, "C_vel_pos": …,
//               "B_vel_pos": …, "A_pos": …, "P_pos": …, "S_pos": …},
//    "stick": {"dv": …, "D_neg": …, "D_pos": …}}          (optional, Eq. 7)
// Missing parameters are zero (P_pos defaults to 1); unknown ones are errors.
#pragma once

#include <filesystem>
#include <string_view>

#include "knoblab/sim/knob.hpp"

namespace knoblab::cli {

sim::KnobParams parse_knob_json(std::string_view text, std::string_view source_name);
sim::KnobParams read_knob_file(const std::filesystem::path& path);

}  // namespace knoblab::cli
