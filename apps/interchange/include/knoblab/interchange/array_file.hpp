// Numeric arrays from the files other tools save, told apart by their first
// bytes (not their names): MATLAB MAT v5, v7 and v7.3 (mat5.hpp), NumPy .npy
// and .npz (npy.hpp). Every kind gives MatArrays shaped alike and MatErrors.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "knoblab/interchange/mat5.hpp"

namespace knoblab::interchange {

enum class ArrayFileKind { kNone, kMat, kNpy, kNpz };

// What the file's first bytes (32 are enough) say it is; kNone for anything
// else (a CSV).
ArrayFileKind array_file_kind(std::string_view first_bytes);

// Every variable (MAT), the one array (.npy, named after the file's stem) or
// every member (.npz). A MatError for a file that is none of these.
std::vector<MatArray> read_array_file(const std::filesystem::path& path, const MatLimits& limits = {});

// The array called `name` among `arrays`; a MatError listing those present
// when it is missing.
MatArray take_array(std::vector<MatArray>& arrays, std::string_view name, const std::string& source);

}  // namespace knoblab::interchange
