// The recording's motion as the findings' sentences speak of it: whether
// the velocity reverses beyond noise, and where in time and angle an effect
// changed the model's torque. Internal to knoblab_discovery.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "knoblab/fit/fit_data.hpp"

namespace knoblab::discovery::detail {

// Turns of the motion that then travel back more than `travel` (rad) from
// where they turned: the velocity's sign changes beyond noise. A stop and a
// start the same way, encoder noise, or the few µrad a motor snaps back by
// at a breakaway are no reversal.
std::size_t count_reversals(std::span<const double> theta, double travel);

// "t 0.02–0.31 s, θ −57…−40°" ("x −5.1…−4 mm" on a linear axis): where the rows `rows` of `d` (in time order)
// hold the middle 90 % of the squared change from residual `before` to
// `after` (rows where either is NaN left out); "" when nothing changed.
std::string effect_span(const fit::FitData& d, std::span<const std::size_t> rows,
                        const std::vector<double>& before, const std::vector<double>& after);

}  // namespace knoblab::discovery::detail
