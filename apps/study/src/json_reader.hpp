// The study files read through the shared JSON reader (apps/jsonread), whose
// PathError is the study's ProtocolError.
#pragma once

#include "knoblab/jsonread/json_reader.hpp"

namespace knoblab::study::detail {
using namespace knoblab::jsonread;  // NOLINT(google-build-using-namespace): the study's own reading vocabulary
}  // namespace knoblab::study::detail
