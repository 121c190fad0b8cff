// Reading MATLAB MAT-files: level 5 (what save -v6 and save -v7 write, and
// scipy.io.savemat) and v7.3 (save -v7.3: HDF5, read through libhdf5).
// Outside recordings arrive this way. Numeric arrays and cell arrays are
// read; structs, sparse, complex and objects are listed but their contents
// are not. Both versions give the same MatArray for the same variable.
//
// The reader trusts nothing in the file: every size is checked against the
// bytes present, nesting and inflated sizes are capped, and anything off is
// a MatError naming the file offset (v5) or the variable and cell (v7.3).
// The NumPy readers (npy.hpp) give MatArrays and MatErrors too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace knoblab::interchange {

// MATLAB's array classes (mxClassID), as stored in the array flags.
enum class MatClass : std::uint8_t {
  kCell = 1, kStruct = 2, kObject = 3, kChar = 4, kSparse = 5,
  kDouble = 6, kSingle = 7, kInt8 = 8, kUInt8 = 9, kInt16 = 10, kUInt16 = 11,
  kInt32 = 12, kUInt32 = 13, kInt64 = 14, kUInt64 = 15, kFunction = 16, kOpaque = 17,
};

struct MatArray {
  std::string name;                 // empty inside cell arrays
  MatClass cls = MatClass::kDouble;
  bool logical = false;             // a uint8 array flagged logical
  bool complex = false;             // complex numeric: values stay empty
  std::vector<std::size_t> dims;    // at least one; column-major like MATLAB
  std::vector<double> values;       // numeric (real, incl. logical) only, converted to double
  std::vector<MatArray> cells;      // cell arrays only, column-major

  bool is_cell() const { return cls == MatClass::kCell; }
  // A real numeric or logical array: `values` holds its elements.
  bool is_numeric() const;
  std::size_t numel() const;
  std::size_t rows() const { return dims.empty() ? 0 : dims[0]; }
  std::size_t cols() const;  // product of every dimension after the first
  // Column-major access; throws std::out_of_range.
  double at(std::size_t row, std::size_t col) const;
  const MatArray& cell(std::size_t row, std::size_t col) const;
  // "3x4306 double", "4x50 cell", "1x1 struct": for messages.
  std::string describe() const;
};

// Caps that keep a hostile or broken file from costing much memory or time.
struct MatLimits {
  std::size_t max_file_bytes = std::size_t{2} << 30;
  std::size_t max_inflated_bytes = std::size_t{1} << 30;  // per compressed element
  std::size_t max_depth = 32;                             // cells within cells
  std::size_t max_arrays = 1'000'000;                     // cells count too
};

class MatError : public std::runtime_error {
 public:
  // what() is "source: offset N: reason" ("source: reason" for the whole file
  // and for v7.3 files, whose reason names the variable).
  MatError(std::string source, std::size_t offset, std::string reason, bool whole_file = false);
  std::size_t offset() const { return offset_; }
  const std::string& reason() const { return reason_; }

 private:
  std::size_t offset_;
  std::string reason_;
};

// Every named top-level variable, in file order (v7.3: in name order, as
// HDF5 lists them).
std::vector<MatArray> parse_mat(std::string_view bytes, std::string_view source_name,
                                const MatLimits& limits = {});
std::vector<MatArray> read_mat(const std::filesystem::path& path, const MatLimits& limits = {});

// One variable; a MatError listing the variables present when it is missing.
MatArray read_mat_variable(const std::filesystem::path& path, std::string_view name,
                           const MatLimits& limits = {});

}  // namespace knoblab::interchange
