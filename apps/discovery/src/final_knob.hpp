// The final extended model as a knob (DiscrepancyResult::final_knob).
// Internal to knoblab_discovery.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <span>

#include "extended_model.hpp"
#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::discovery::detail {

FinalKnob final_knob_of(const ExtendedModel& m, const std::optional<fit::StickBand>& stick);

// The inverse: a knob's terms as the extended model fits them (Eq. 6 free,
// its detents only when the knob has them; each effect's parameters and
// setting from the table's names). final_knob_of(extended_of(k), k.stick)
// gives k back. Throws std::invalid_argument for an effect the table
// refuses.
ExtendedModel extended_of(const FinalKnob& k);

// One effect's parameters as a model file carries them: the reported ones
// without the values derived beside them.
Params settable_params(const ActiveEffect& e, const ExtendedModel& m);

// A model file's fields from the knob's terms: "model", "params", "stick",
// "effects" and "render" (the base reduced to Eq. 14 over `omega`).
nlohmann::ordered_json model_file_fields(const FinalKnob& k, std::span<const double> omega);

}  // namespace knoblab::discovery::detail
