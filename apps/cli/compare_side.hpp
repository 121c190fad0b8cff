// One side of `knoblab compare`: a capture (CSV file, or a capture id in
// --db) fitted now or by its latest stored thesis6 fit, or a JSON file — a
// fit's result (`fit --json`, `fit-export`), a render model (`fit
// --render-model`) or a model file (`discrepancy --model-out`).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "args.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::cli {

struct SideParam {
  std::string name;  // Eq. 6 / Eq. 14 names, dv, D_neg, D_pos, "effect.param"
  double value = 0.0;
  std::optional<std::array<double, 2>> ci95;  // none: held, or the file has no intervals
};

struct CompareSide {
  std::string label;   // "a.csv", "capture 3 (moderate-detents)", "fit.json"
  std::string origin;  // "fitted now", "stored fit 4", "fit result", "render model", "model file"
  std::vector<SideParam> params;
  model::ThesisModel<double> model;  // Eq. 6's terms, for the curves (render4: C = 0, B± = B)
  std::optional<fit::FitData> data;  // a capture's prepared samples, for the clouds
};

// `operand` is a file, or with --db a capture id. Throws UsageError for an
// operand that is neither, std::runtime_error / std::invalid_argument for
// one that cannot be read (naming it).
CompareSide read_side(const std::string& operand, const Args& args);

}  // namespace knoblab::cli
