// Test-only MAT v7.3 writer through the HDF5 C API, laid out as MATLAB's
// save -v7.3 lays it out: a 512-byte user block starting with the MATLAB
// text header, variables as root datasets stored transposed with a
// MATLAB_class attribute, cells as object references into "#refs#".
#pragma once

#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace knoblab::test::mat73 {

class File {
 public:
  explicit File(std::filesystem::path path) : path_(std::move(path)) {
    const hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    H5Pset_userblock(fcpl, 512);
    file_ = H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
    H5Pclose(fcpl);
    if (file_ < 0) throw std::runtime_error("H5Fcreate " + path_.string());
  }
  ~File() { close(); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;

  // A rows x cols numeric array from column-major values, stored as HDF5
  // dims [cols, rows] of `file_type` (H5T_IEEE_F64LE, H5T_STD_I16LE, ...).
  // Returns the dataset's path.
  std::string numeric(const std::string& path, int rows, int cols, const std::vector<double>& values,
                      const std::string& cls = "double", hid_t file_type = H5T_IEEE_F64LE) {
    const hsize_t dims[2] = {static_cast<hsize_t>(cols), static_cast<hsize_t>(rows)};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t set = H5Dcreate2(file_, path.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (!values.empty()) H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    class_attribute(set, cls);
    H5Dclose(set);
    H5Sclose(space);
    return path;
  }

  // A rows x cols cell array whose cells are the datasets at `targets`
  // (column-major), made with numeric() under "/#refs#/".
  void cell(const std::string& path, int rows, int cols, const std::vector<std::string>& targets) {
    std::vector<hobj_ref_t> refs(targets.size());
    for (std::size_t i = 0; i < targets.size(); ++i)
      H5Rcreate(&refs[i], file_, targets[i].c_str(), H5R_OBJECT, -1);
    const hsize_t dims[2] = {static_cast<hsize_t>(cols), static_cast<hsize_t>(rows)};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t set = H5Dcreate2(file_, path.c_str(), H5T_STD_REF_OBJ, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(set, H5T_STD_REF_OBJ, H5S_ALL, H5S_ALL, H5P_DEFAULT, refs.data());
    class_attribute(set, "cell");
    H5Dclose(set);
    H5Sclose(space);
  }

  // "/#refs#", where MATLAB keeps the cells' contents.
  std::string refs(const std::string& name) {
    if (H5Lexists(file_, "/#refs#", H5P_DEFAULT) <= 0) H5Gclose(H5Gcreate2(file_, "/#refs#", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    return "/#refs#/" + name;
  }

  // A struct: a group with MATLAB_class "struct" and one field.
  void structure(const std::string& path) {
    const hid_t g = H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    class_attribute(g, "struct");
    H5Gclose(g);
    numeric(path + "/field", 1, 1, {1});
  }

  // An empty array: MATLAB_empty = 1, its dims as the data.
  void empty(const std::string& path, std::uint64_t rows, std::uint64_t cols) {
    const hsize_t dims[1] = {2};
    const std::uint64_t data[2] = {rows, cols};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t set = H5Dcreate2(file_, path.c_str(), H5T_STD_U64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(set, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    class_attribute(set, "double");
    const hid_t aspace = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(set, "MATLAB_empty", H5T_STD_U8LE, aspace, H5P_DEFAULT, H5P_DEFAULT);
    const std::uint8_t one = 1;
    H5Awrite(attr, H5T_NATIVE_UINT8, &one);
    H5Aclose(attr);
    H5Sclose(aspace);
    H5Dclose(set);
    H5Sclose(space);
  }

  hid_t id() const { return file_; }

  // Closes the HDF5 file and writes MATLAB's text header into the user block.
  void close() {
    if (file_ < 0) return;
    H5Fclose(file_);
    file_ = -1;
    std::string header = "MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: knoblab test HDF5 schema 1.00 .";
    header.resize(116, ' ');
    header.append(8, '\0');
    header += std::string("\x00\x02", 2) + "IM";
    std::fstream f(path_, std::ios::in | std::ios::out | std::ios::binary);
    f.write(header.data(), static_cast<std::streamsize>(header.size()));
  }

  static void class_attribute(hid_t obj, const std::string& cls) {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, cls.size());
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attr = H5Acreate2(obj, "MATLAB_class", type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attr, type, cls.data());
    H5Aclose(attr);
    H5Sclose(space);
    H5Tclose(type);
  }

 private:
  std::filesystem::path path_;
  hid_t file_ = -1;
};

}  // namespace knoblab::test::mat73
