// The final extended model as a knob (DiscrepancyResult::final_knob).
// Internal to knoblab_discovery.
#pragma once

#include <optional>

#include "extended_model.hpp"
#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::discovery::detail {

FinalKnob final_knob_of(const ExtendedModel& m, const std::optional<fit::StickBand>& stick);

}  // namespace knoblab::discovery::detail
