// MAT v7.3 files (MATLAB's save -v7.3): HDF5 behind a 512-byte MATLAB
// header, read through libhdf5. parse_mat hands them here.
#pragma once

#include <string_view>
#include <vector>

#include "knoblab/interchange/mat5.hpp"

namespace knoblab::interchange::detail {

std::vector<MatArray> parse_mat73(std::string_view bytes, const std::string& source, const MatLimits& limits);

}  // namespace knoblab::interchange::detail
