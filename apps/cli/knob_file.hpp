// Knob parameters from a JSON file, so a fitted or hand-designed knob can be
// simulated. The formats are the fit's own (SI units, docs/fit.md): its
// result JSON (`knoblab fit --json`) and its render-model file
// (`--render-model`), read as they are written:
//   {"model": "thesis6",
//    "params": {"M_acc": …, "C_vel_neg": …, "B_vel_neg": …, "C_vel_pos": …,
//               "B_vel_pos": …, "A_pos": …, "P_pos": …, "S_pos": …},
//    "stick": {"dv": …, "D_neg": …, "D_pos": …} or null}     (Eq. 7, optional)
//   {"model": "render4",
//    "params": {"M_acc": …, "B_vel": …, "A_pos": …, "P_pos": …,
//               "dv": …, "D_neg": …, "D_pos": …}}           (Eq. 14)
// A file without "model" is thesis6. Missing parameters are zero (P_pos
// defaults to 1); an unknown parameter is an error that lists the known
// ones. The result's figures beside the parameters (ci95, se, detents, rmse,
// stick.samples, …) are not parameters and are ignored, as is a model
// file's "render" (hapticd's). A model file (`knoblab discrepancy
// --model-out`, docs/discrepancy.md) adds effects under the names
// discrepancy reports and simulate --effects takes, checked against the
// effect table (model/effect_table.hpp, effect_json.hpp):
//    "effects": [{"effect": "stribeck",
//                 "params": {"static_excess_Nm": …, "stribeck_velocity_rad_s": …}}, …]
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "knoblab/sim/knob.hpp"
#include "knoblab/model/effect_table.hpp"
#include "knoblab/sim/library_effects.hpp"

namespace knoblab::cli {

struct KnobFile {
  sim::KnobParams knob;
  std::vector<model::EffectSpec> effects;  // beyond the knob's own terms, for simulate()
};

KnobFile parse_knob_json(std::string_view text, std::string_view source_name);
KnobFile read_knob_file(const std::filesystem::path& path);

}  // namespace knoblab::cli
