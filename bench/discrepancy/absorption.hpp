// How much of an effect's torque the base model cannot take up. Eq. 6's own
// terms absorb part of many effects when the base is fitted: a quadratic
// drag mostly becomes more viscous damping, a Stribeck excess mostly more
// Coulomb friction, a spring partly a once-per-revolution detent. Only the
// rest is a discrepancy: the fit leaves it in the residual, and it alone can
// meet discovery's held-out bar. The sweep sizes effects by that rest.
//
// The effect's change is taken on the residuals under the clean knob's fit,
// the capture's less the clean capture's (the same seed: the sensor noise
// cancels), so that what Eq. 6 predicts of a changed motion (a PID loop
// tracking differently) does not count. The base's refit is linearised
// about the clean fit: that change is projected on the sensitivities of
// Eq. 6 to each of its parameters, on the clean capture's motion, and what
// the projection leaves is the unabsorbed part.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::bench {

// RMS over `rows` (of both captures: a row is a sample time) of the change
// in residual under `params` (the clean knob's fitted Eq. 6, in
// model::ThesisParam order) from `clean` to `captured`, less its
// least-squares projection on Eq. 6's sensitivities there.
double unabsorbed_rms(const std::array<double, model::kThesisParamCount>& params, const fit::FitData& clean,
                      const fit::FitData& captured, const std::vector<std::size_t>& rows);

}  // namespace knoblab::bench
