// A model given on the command line (fit --model FILE, discrepancy --model
// FILE): a model file, a fit's JSON or a render model, read and checked.
#pragma once

#include <string>

#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::cli {

struct ModelInput {
  discovery::FinalKnob knob;
  std::string text;  // the file as read, for provenance
};

// Throws UsageError naming the file and what is wrong with it.
ModelInput read_model_input(const std::string& path);

}  // namespace knoblab::cli
