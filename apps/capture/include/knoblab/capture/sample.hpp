// The loop records the interchange Sample: the same record the store and the
// CSV hold, so nothing converts between look-alike structs.
#pragma once

#include "knoblab/interchange/sample.hpp"

namespace knoblab::capture {
using interchange::Sample;
}  // namespace knoblab::capture
