// What a fit says that no real knob does, in sentences for the person who
// reads the fit: friction that pushes the knob along (an energy-producing
// knob), negative inertia, an inertia the capture did not identify. A fit is
// still returned: the sentences say what to distrust and what to check.
#pragma once

#include <string>
#include <vector>

#include "knoblab/fit/knob_fit.hpp"

namespace knoblab::fit {

// Empty when every fitted value is physically possible. A value is flagged
// only when its 95 % interval is on the wrong side of zero as a whole: one
// that merely reaches zero is not resolved, not unphysical.
std::vector<std::string> physical_warnings(const FitResult& r);

}  // namespace knoblab::fit
