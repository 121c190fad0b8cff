// Reduction of a fitted knob to the rendering model (thesis Eq. 14 and the
// optional Karnopp stick band, Eq. 7) and the model file hapticd loads.
//
// Eq. 14 has one damping coefficient and no Coulomb term or detent phase:
//   B_vel = the viscous coefficient that best matches the fitted friction
//           C·sgn θ̇ + B·θ̇ (both directions) over the velocities captured, in
//           the least-squares sense;
//   A_pos = |A|, P_pos = P (S is a property of where the capture started);
//   the stick band carries over (dv, D_neg, D_pos), when the fit found one.
// The file is the `load_model` command's arguments (docs/protocol.md):
//   {"model": "render4", "params": {"M_acc": …, "B_vel": …, "A_pos": …,
//    "P_pos": …, "dv": …, "D_neg": …, "D_pos": …}}
#pragma once

#include <optional>
#include <span>
#include <string>

#include "knoblab/fit/knob_fit.hpp"

namespace knoblab::fit {

struct RenderModelFile {
  double M_acc = 0.0, B_vel = 0.0, A_pos = 0.0, P_pos = 1.0;
  std::optional<StickBand> stick;
};

// `omega` are the velocities captured (the B_vel match is over them).
RenderModelFile reduce_to_render(const FitResult& r, std::span<const double> omega);

std::string to_json(const RenderModelFile& m);
// Throws std::invalid_argument with the offending key for a malformed file.
RenderModelFile parse_render_model(const std::string& json_text);

}  // namespace knoblab::fit
