// Reading NumPy's array files: .npy (np.save: format versions 1.0, 2.0 and
// 3.0) and .npz (np.savez / np.savez_compressed: a zip archive of .npy
// members, stored or deflated). Arrays come back as MatArray, shaped as the
// MAT reader shapes the same data saved by scipy.io.savemat: a 2-D array of
// shape (R, C) is R x C, a 1-D array of N values is 1 x N, a 0-D one 1 x 1.
//
// Numeric dtypes are read (float64, float32, signed and unsigned integers of
// 1 to 8 bytes, bool), in either byte order and in C or Fortran order.
// Nothing in a file is executed: object arrays (pickles), structured,
// complex, string and date dtypes, arrays of more than two dimensions and
// shapes the bytes cannot hold are refused with a MatError naming the file
// offset (npz: the member and the offset inside it).
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "knoblab/interchange/mat5.hpp"

namespace knoblab::interchange {

// One .npy file's bytes; the array's name is empty.
MatArray parse_npy(std::string_view bytes, std::string_view source_name, const MatLimits& limits = {});

// Every .npy member of a .npz archive, in archive order, named as np.load
// names them (the member name without ".npy"). Members of other kinds are an
// error: np.savez writes none.
std::vector<MatArray> parse_npz(std::string_view bytes, std::string_view source_name,
                                const MatLimits& limits = {});

}  // namespace knoblab::interchange
