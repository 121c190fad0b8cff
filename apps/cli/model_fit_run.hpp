// `knoblab fit CAPTURE --model MODEL.json`: a model file's terms (Eq. 6 and
// the effects discrepancy found) fitted to a capture, printed with their
// intervals and written back as a model file (docs/fit.md, "Fitting a model
// file").
#pragma once

#include <string>

#include "args.hpp"

namespace knoblab::cli {

// `model_path` names the model file --model gave.
int run_fit_model_file(const Args& args, const std::string& model_path);

}  // namespace knoblab::cli
