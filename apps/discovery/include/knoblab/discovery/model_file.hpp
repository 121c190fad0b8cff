// A model file (docs/discrepancy.md, "Model file"): Eq. 6, its stick band and
// effects from the library under the effect table's names. Discrepancy's
// --model-out writes one; simulate --params, hapticd --model and
// `knoblab fit --model FILE` take one. Here: reading it back, and fitting its
// terms to another capture.
//
//   FinalKnob start = parse_model_file(text, "knob-model.json");
//   ModelFit f = fit_model(fit::prepare(capture), start);
//   f.knob.effects[0].params, f.effect_ci95[0], f.rmse_Nm
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/run_hooks.hpp"

namespace knoblab::discovery {

// The model's terms: "params" (Eq. 6, the fit's names; missing ones 0, P_pos
// 1), "stick" (or null), "effects" (each checked against the effect table:
// names, ranges, what it needs). A fit's JSON (no effects) reads too, and a
// render model ("render4": M_acc, B_vel both ways, no Coulomb level, the band
// among its params; without S_pos its detent phase is unknown); other
// top-level fields ("render", "source", "ci95", a fit's figures) are not
// the model's and are ignored. Throws std::invalid_argument naming `source`
// and the field.
FinalKnob parse_model_file(std::string_view json_text, std::string_view source);

// The model's terms fitted to a capture: Eq. 6 (the detents only when the
// model has them) and every effect's continuous parameters, jointly (Ceres,
// autodiff through model/effects.hpp, as discovery fits them), from the
// model's values; the operators' settings (backlash width, delay, clip
// limit, presliding angle, endstop position, drift's t₀, the coupling) and the stick band are held as given. Rows slower than the stick
// band (and than 2 % of the brisk speed) are left out, as discovery leaves
// them. Intervals: the sandwich estimate (knoblab/fit/covariance.hpp).
struct ModelFit {
  FinalKnob knob;
  std::vector<double> base_ci95;    // Eq. 6, fit order; NaN: held
  std::vector<Params> effect_ci95;  // per effect, the names of knob.effects[i]; NaN: held
  double rmse_Nm = 0.0;
  std::size_t rows = 0;             // the rows fitted (moving, described)
  double seconds = 0.0;
};
// Throws fit::FitDataError when the capture cannot identify the model,
// fit::Cancelled when hooks say so.
ModelFit fit_model(const fit::FitData& data, const FinalKnob& start, const fit::RunHooks& hooks = {});

// The fitted model as a model file, with "ci95" ({"params": {…}, "effects":
// [{…}]}, SI, null where held) and "rmse_Nm", "rows" beside it; `input`
// names the capture, `model_source` the file the terms came from.
std::string model_file_json(const ModelFit& f, std::span<const double> omega, const std::string& input,
                            const std::string& model_source);

}  // namespace knoblab::discovery
