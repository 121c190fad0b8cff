// MAT v7.3 layout: an HDF5 file with a 512-byte user block holding MATLAB's
// text header. Each variable is a root-level dataset (or group, for structs)
// with a MATLAB_class attribute naming its class. Arrays are stored
// transposed: an R x C matrix is an HDF5 dataset of dims [C, R], so HDF5's
// row-major data is MATLAB's column-major order and the dims only need
// reversing. A cell array is a dataset of object references to datasets in
// the "#refs#" group; an empty array (MATLAB_empty = 1) stores its dims as
// its data; sparse arrays are groups marked MATLAB_sparse; complex data is a
// compound {real, imag}. Names starting with '#' are MATLAB's bookkeeping.
#include "mat73_reader.hpp"

#include <hdf5.h>

#include <climits>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace knoblab::interchange::detail {

namespace {

// libhdf5 prints its error stack to stderr by default; the messages here say
// what went wrong instead.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

// The innermost message on libhdf5's error stack, for our own messages.
std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD,
           [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
             if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
             return 0;
           },
           &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? "libhdf5 gave no reason" : reason;
}

// An HDF5 identifier closed when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// References read from a dataset, released however the reading ends.
struct References {
  explicit References(std::size_t n) : refs(n) {}
  ~References() {
    if (read)
      for (auto& r : refs) H5Rdestroy(&r);
  }
  References(const References&) = delete;
  References& operator=(const References&) = delete;
  H5R_ref_t* data() { return refs.data(); }
  std::vector<H5R_ref_t> refs;
  bool read = false;
};

std::optional<MatClass> numeric_class(const std::string& name) {
  static constexpr std::pair<std::string_view, MatClass> kClasses[] = {
      {"double", MatClass::kDouble}, {"single", MatClass::kSingle}, {"int8", MatClass::kInt8},
      {"uint8", MatClass::kUInt8},   {"int16", MatClass::kInt16},   {"uint16", MatClass::kUInt16},
      {"int32", MatClass::kInt32},   {"uint32", MatClass::kUInt32}, {"int64", MatClass::kInt64},
      {"uint64", MatClass::kUInt64}, {"logical", MatClass::kUInt8}};
  for (auto [n, c] : kClasses)
    if (n == name) return c;
  return std::nullopt;
}

class Reader {
 public:
  Reader(const std::string& source, const MatLimits& limits) : source_(source), limits_(limits) {}

  [[noreturn]] void fail(const std::string& where, const std::string& reason) const {
    throw MatError(source_, 0, where + ": " + reason, true);
  }

  // A string attribute (fixed or variable length), or nullopt when absent.
  std::optional<std::string> string_attribute(hid_t obj, const char* name, const std::string& where) const {
    if (H5Aexists(obj, name) <= 0) return std::nullopt;
    Handle attr(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
    Handle type(attr.ok() ? H5Aget_type(attr.get()) : -1, H5Tclose);
    if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING)
      fail(where, std::string("attribute ") + name + " is not a string");
    Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
    if (H5Tis_variable_str(type.get()) > 0) {
      H5Tset_size(mem.get(), H5T_VARIABLE);
      char* text = nullptr;
      if (H5Aread(attr.get(), mem.get(), &text) < 0 || !text)
        fail(where, std::string("cannot read attribute ") + name + ": " + hdf5_reason());
      std::string s(text);
      H5free_memory(text);
      return s;
    }
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0 || size > 1024) fail(where, std::string("attribute ") + name + " of " + std::to_string(size) + " bytes");
    std::string s(size, '\0');
    H5Tset_size(mem.get(), size);
    if (H5Aread(attr.get(), mem.get(), s.data()) < 0)
      fail(where, std::string("cannot read attribute ") + name + ": " + hdf5_reason());
    s.resize(s.find('\0') == std::string::npos ? s.size() : s.find('\0'));
    return s;
  }

  // An integer attribute that MATLAB sets to 1 (MATLAB_empty), or 0 when absent.
  std::uint64_t integer_attribute(hid_t obj, const char* name, const std::string& where) const {
    if (H5Aexists(obj, name) <= 0) return 0;
    Handle attr(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose);
    Handle space(attr.ok() ? H5Aget_space(attr.get()) : -1, H5Sclose);
    std::uint64_t v = 0;
    if (!space.ok() || H5Sget_simple_extent_npoints(space.get()) != 1 ||
        H5Aread(attr.get(), H5T_NATIVE_UINT64, &v) < 0)
      fail(where, std::string("attribute ") + name + " is not one integer");
    return v;
  }

  MatArray read_object(hid_t obj, const std::string& where, std::size_t depth) {
    if (depth > limits_.max_depth)
      fail(where, "arrays nested deeper than " + std::to_string(limits_.max_depth) + " levels");
    if (++arrays_ > limits_.max_arrays)
      fail(where, "more than " + std::to_string(limits_.max_arrays) + " arrays (the limit)");
    H5O_info2_t info;
    if (H5Oget_info3(obj, &info, H5O_INFO_BASIC) < 0) fail(where, "cannot read: " + hdf5_reason());
    const std::string cls = string_attribute(obj, "MATLAB_class", where).value_or("");
    MatArray a;
    if (info.type == H5O_TYPE_GROUP) {  // a struct, a sparse matrix or an object: listed only
      a.cls = integer_attribute(obj, "MATLAB_sparse", where) != 0 ? MatClass::kSparse
              : cls == "struct"                                    ? MatClass::kStruct
                                                                   : MatClass::kObject;
      a.dims = {1, 1};
      return a;
    }
    if (info.type != H5O_TYPE_DATASET) fail(where, "neither a dataset nor a group");
    if (cls.empty()) fail(where, "no MATLAB_class attribute: not a variable MATLAB wrote");

    Handle space(H5Dget_space(obj), H5Sclose);
    const int rank = space.ok() ? H5Sget_simple_extent_ndims(space.get()) : -1;
    if (rank < 0 || rank > 32) fail(where, "unreadable dataspace");
    std::vector<hsize_t> h5dims(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space.get(), h5dims.data(), nullptr);
    a.dims.assign(h5dims.rbegin(), h5dims.rend());  // MATLAB's order
    if (a.dims.empty()) a.dims = {1, 1};
    std::size_t n = 1;
    for (std::size_t d : a.dims) {
      if (d != 0 && n > SIZE_MAX / d) fail(where, "dimensions overflow 64 bits");
      n *= d;
    }

    if (integer_attribute(obj, "MATLAB_empty", where) != 0) {
      // The data is the empty array's dims (e.g. [0 3]), no elements.
      if (n > 32) fail(where, "an empty array's dims hold " + std::to_string(n) + " values");
      std::vector<std::uint64_t> dims(n);
      if (n > 0 && H5Dread(obj, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, dims.data()) < 0)
        fail(where, "cannot read an empty array's dims: " + hdf5_reason());
      a.dims.assign(dims.begin(), dims.end());
      if (a.dims.empty()) a.dims = {0, 0};
      a.cls = cls == "cell" ? MatClass::kCell : numeric_class(cls).value_or(MatClass::kDouble);
      a.logical = cls == "logical";
      return a;
    }

    Handle type(H5Dget_type(obj), H5Tclose);
    const H5T_class_t tclass = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
    if (cls == "cell") {
      a.cls = MatClass::kCell;
      if (tclass != H5T_REFERENCE) fail(where, "a cell array whose data are not object references");
      if (n > limits_.max_arrays) fail(where, "cell array of " + std::to_string(n) + " cells, over the limit");
      // Read as HDF5's current reference type, which also reads MATLAB's old-style object references.
      References refs(n);
      if (n > 0 && H5Dread(obj, H5T_STD_REF, H5S_ALL, H5S_ALL, H5P_DEFAULT, refs.data()) < 0)
        fail(where, "cannot read the cell references: " + hdf5_reason());
      refs.read = true;
      a.cells.reserve(n);
      for (std::size_t i = 0; i < n; ++i) {
        const std::string cell_where = where + ", cell " + std::to_string(i + 1);
        Handle target(H5Ropen_object(&refs.refs[i], H5P_DEFAULT, H5P_DEFAULT), H5Oclose);
        if (!target.ok()) fail(cell_where, "broken reference: " + hdf5_reason());
        a.cells.push_back(read_object(target.get(), cell_where, depth + 1));
      }
      return a;
    }
    if (cls == "char") {
      a.cls = MatClass::kChar;
      return a;
    }
    const auto numeric = numeric_class(cls);
    if (!numeric) {  // function handles, strings, tables, other objects: listed only
      a.cls = MatClass::kObject;
      return a;
    }
    a.cls = *numeric;
    a.logical = cls == "logical";
    if (tclass == H5T_COMPOUND) {  // {real, imag}
      a.complex = true;
      return a;
    }
    if (tclass != H5T_INTEGER && tclass != H5T_FLOAT) fail(where, "class " + cls + " but the data are not numbers");
    if (n > limits_.max_inflated_bytes / sizeof(double))
      fail(where, std::to_string(n) + " values, over the " + std::to_string(limits_.max_inflated_bytes) +
                      "-byte limit");
    a.values.resize(n);
    if (n > 0 && H5Dread(obj, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.values.data()) < 0)
      fail(where, "cannot read the data: " + hdf5_reason());
    return a;
  }

 private:
  const std::string& source_;
  const MatLimits& limits_;
  std::size_t arrays_ = 0;
};

}  // namespace

std::vector<MatArray> parse_mat73(std::string_view bytes, const std::string& source, const MatLimits& limits) {
  const QuietErrors quiet;
  Reader reader(source, limits);
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // The core driver reads the file from memory: a copy of the bytes already read.
  if (!fapl.ok() || H5Pset_fapl_core(fapl.get(), 1 << 20, false) < 0 ||
      H5Pset_file_image(fapl.get(), const_cast<char*>(bytes.data()), bytes.size()) < 0)
    reader.fail("MAT v7.3", "cannot set up libhdf5: " + hdf5_reason());
  // The core driver refuses an image whose name exists on disk; nothing can exist under /dev/null.
  Handle file(H5Fopen("/dev/null/knoblab-mat73-image", H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!file.ok()) reader.fail("MAT v7.3", "not a readable HDF5 file (truncated or corrupt?): " + hdf5_reason());

  H5G_info_t group;
  if (H5Gget_info(file.get(), &group) < 0) reader.fail("MAT v7.3", "cannot list the variables: " + hdf5_reason());
  if (group.nlinks > limits.max_arrays) reader.fail("MAT v7.3", std::to_string(group.nlinks) + " variables, over the limit");
  std::vector<MatArray> vars;
  for (hsize_t i = 0; i < group.nlinks; ++i) {
    const ssize_t len = H5Lget_name_by_idx(file.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0 || len > 4096) reader.fail("MAT v7.3", "cannot read variable name " + std::to_string(i + 1));
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(file.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    if (name.starts_with('#')) continue;  // #refs#, #subsystem#
    std::string printable;
    for (char c : name) printable += (c >= 0x20 && c < 0x7f) ? c : '?';
    Handle obj(H5Oopen(file.get(), name.c_str(), H5P_DEFAULT), H5Oclose);
    if (!obj.ok()) reader.fail("variable '" + printable + "'", "cannot open: " + hdf5_reason());
    MatArray a = reader.read_object(obj.get(), "variable '" + printable + "'", 0);
    a.name = printable;
    vars.push_back(std::move(a));
  }
  return vars;
}

}  // namespace knoblab::interchange::detail
