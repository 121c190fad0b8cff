// A whole file in memory for the array readers, refused over the size limit.
#pragma once

#include <filesystem>
#include <string>

#include "knoblab/interchange/mat5.hpp"

namespace knoblab::interchange::detail {

std::string read_file_bytes(const std::filesystem::path& path, const MatLimits& limits);

}  // namespace knoblab::interchange::detail
