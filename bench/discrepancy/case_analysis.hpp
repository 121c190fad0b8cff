// What discovery makes of one benchmark capture: the first finding, the
// held-out RMS before and after, and how long the analysis took.
#pragma once

#include <cstddef>
#include <string>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/interchange/capture.hpp"

namespace knoblab::bench {

struct Analysis {
  std::string named = "none";  // the first reported finding's effect
  std::string tentative;       // the first term found under the reporting bar, if any
  double confidence = 0.0;
  double before = 0.0, after = 0.0;  // held-out RMS, base → final, N·m
  // Base → final on the rows both models describe (DiscrepancyResult::
  // same_rows): before/after are over the rows each describes, and a model
  // that leaves rows undescribed (a twist's creeping knob, a delay's rows
  // moved into the stick band) sheds their residual from `after`.
  double same_rows_gain = 0.0;
  double seconds = 0.0;  // prepare + discover
  std::size_t samples = 0;
  std::string json;      // discovery's result
};

// Prepares the capture as `knoblab discrepancy` does and runs discovery on
// it, timed; `prepared`: where to leave the capture as the analysis saw it.
Analysis analyse(const interchange::Capture& capture, fit::FitData* prepared = nullptr);

}  // namespace knoblab::bench
