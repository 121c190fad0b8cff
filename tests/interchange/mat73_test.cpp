// MAT v7.3 reader: files written here through the HDF5 C API as MATLAB
// writes them, read back to the same MatArrays the v5 reader gives for the
// same content; broken and hostile files each give a MatError saying why.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "knoblab/interchange/array_file.hpp"
#include "knoblab/interchange/mat5.hpp"
#include "mat5_writer.hpp"
#include "mat73_writer.hpp"

namespace knoblab::interchange {
namespace {

class Mat73 : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("knoblab-mat73-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path path(const std::string& name) const { return dir_ / name; }

  std::string error_of(const std::filesystem::path& p) const {
    try {
      read_mat(p);
    } catch (const MatError& e) {
      return e.what();
    }
    return "";
  }

  std::filesystem::path dir_;
};

void expect_same(const MatArray& a, const MatArray& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.describe(), b.describe());
  EXPECT_EQ(a.dims, b.dims);
  EXPECT_EQ(a.values, b.values);
  ASSERT_EQ(a.cells.size(), b.cells.size());
  for (std::size_t i = 0; i < a.cells.size(); ++i) expect_same(a.cells[i], b.cells[i]);
}

const std::vector<double> k2x3 = {1.5, -2, 3e-9, 4, 5, 6.25};  // column-major

TEST_F(Mat73, NumericMatrixReadsAsTheV5FileOfTheSameContent) {
  {
    test::mat73::File f(path("m.mat"));
    f.numeric("/data", 2, 3, k2x3);
  }
  const auto v73 = read_mat(path("m.mat"));
  const auto v5 = parse_mat(test::mat5::Writer().header() + test::mat5::Writer().doubles("data", 2, 3, k2x3), "m5.mat");
  ASSERT_EQ(v73.size(), 1u);
  expect_same(v73[0], v5[0]);
  EXPECT_EQ(v73[0].at(0, 1), 3e-9);  // MATLAB's data(1, 2): the transposed storage undone
  EXPECT_EQ(read_array_file(path("m.mat"))[0].values, k2x3);
}

TEST_F(Mat73, IntegerSingleAndLogicalClassesConvertToDouble) {
  {
    test::mat73::File f(path("c.mat"));
    f.numeric("/i", 1, 3, {-32768, 0, 32767}, "int16", H5T_STD_I16BE);
    f.numeric("/s", 1, 2, {0.25, -1}, "single", H5T_IEEE_F32LE);
    f.numeric("/l", 1, 3, {1, 0, 1}, "logical", H5T_STD_U8LE);
    f.numeric("/u", 1, 1, {18446744073709549568.0}, "uint64", H5T_STD_U64LE);
  }
  auto vars = read_mat(path("c.mat"));
  ASSERT_EQ(vars.size(), 4u);  // name order: i, l, s, u
  EXPECT_EQ(take_array(vars, "i", "c.mat").values, (std::vector<double>{-32768, 0, 32767}));
  const MatArray l = take_array(vars, "l", "c.mat");
  EXPECT_EQ(l.describe(), "1x3 logical");
  EXPECT_EQ(l.values, (std::vector<double>{1, 0, 1}));
  const MatArray s = take_array(vars, "s", "c.mat");
  EXPECT_EQ(s.describe(), "1x2 single");
  EXPECT_EQ(s.values, (std::vector<double>{0.25, -1}));
  EXPECT_EQ(take_array(vars, "u", "c.mat").values, (std::vector<double>{18446744073709549568.0}));
}

TEST_F(Mat73, CellArrayOfSegmentsReadsAsTheV5CellArray) {
  // Rows t, theta, torque; two segments: the accel_tests layout.
  const std::vector<std::vector<double>> cells = {{0, 1, 2}, {10, 11, 12}, {7, 7, 7}, {3, 4}, {13, 14}, {8, 8}};
  {
    test::mat73::File f(path("cell.mat"));
    std::vector<std::string> targets;
    for (std::size_t i = 0; i < cells.size(); ++i)
      targets.push_back(f.numeric(f.refs(std::string(1, static_cast<char>('a' + i))), 1,
                                  static_cast<int>(cells[i].size()), cells[i]));
    f.cell("/data", 3, 2, targets);
  }
  const test::mat5::Writer w;
  std::vector<std::string> v5cells;
  for (const auto& c : cells) v5cells.push_back(w.doubles("", 1, static_cast<std::int32_t>(c.size()), c));
  const auto v5 = parse_mat(w.header() + w.cell("data", 3, 2, v5cells), "c5.mat");
  const auto v73 = read_mat(path("cell.mat"));
  ASSERT_EQ(v73.size(), 1u);  // #refs# is MATLAB's bookkeeping, not a variable
  expect_same(v73[0], v5[0]);
  EXPECT_EQ(v73[0].cell(1, 1).values, (std::vector<double>{13, 14}));
}

TEST_F(Mat73, StructsAndEmptyArraysAreListedNotRead) {
  {
    test::mat73::File f(path("s.mat"));
    f.structure("/info");
    f.empty("/nothing", 0, 3);
    f.numeric("/data", 1, 1, {5});
  }
  auto vars = read_mat(path("s.mat"));
  ASSERT_EQ(vars.size(), 3u);
  EXPECT_EQ(take_array(vars, "info", "s.mat").describe(), "1x1 struct");
  const MatArray empty = take_array(vars, "nothing", "s.mat");
  EXPECT_EQ(empty.describe(), "0x3 double");
  EXPECT_TRUE(empty.values.empty());
}

TEST_F(Mat73, BrokenAndHostileFilesSayWhatIsWrong) {
  {
    test::mat73::File f(path("good.mat"));
    f.numeric("/data", 2, 3, k2x3);
  }
  // Cut short: HDF5 cannot find what its superblock points at.
  std::ifstream in(path("good.mat"), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::ofstream(path("cut.mat"), std::ios::binary).write(bytes.data(), 1200);
  EXPECT_NE(error_of(path("cut.mat")).find("cut.mat: MAT v7.3: not a readable HDF5 file"), std::string::npos)
      << error_of(path("cut.mat"));
  // The header says v7.3 but no HDF5 follows.
  std::ofstream(path("text.mat"), std::ios::binary) << bytes.substr(0, 128) << std::string(600, 'x');
  EXPECT_NE(error_of(path("text.mat")).find("not a readable HDF5 file"), std::string::npos) << error_of(path("text.mat"));
  {
    test::mat73::File f(path("plain.mat"));
    const hsize_t dims[1] = {3};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    H5Dclose(H5Dcreate2(f.id(), "/x", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    H5Sclose(space);
  }
  EXPECT_NE(error_of(path("plain.mat")).find("variable 'x': no MATLAB_class attribute"), std::string::npos)
      << error_of(path("plain.mat"));
  {
    test::mat73::File f(path("fake_cell.mat"));
    f.numeric("/c", 1, 2, {1, 2}, "cell");
  }
  EXPECT_NE(error_of(path("fake_cell.mat")).find("variable 'c': a cell array whose data are not object references"),
            std::string::npos);
  {
    // Two cells that hold each other: the nesting limit stops the reader.
    test::mat73::File f(path("loop.mat"));
    f.cell("/c", 1, 1, {f.numeric(f.refs("placeholder"), 1, 1, {0})});
    f.cell("/#refs#/b", 1, 1, {"/c"});
    hobj_ref_t back;
    H5Rcreate(&back, f.id(), "/#refs#/b", H5R_OBJECT, -1);
    const hid_t c = H5Dopen2(f.id(), "/c", H5P_DEFAULT);
    H5Dwrite(c, H5T_STD_REF_OBJ, H5S_ALL, H5S_ALL, H5P_DEFAULT, &back);
    H5Dclose(c);
  }
  EXPECT_NE(error_of(path("loop.mat")).find("nested deeper than 32 levels"), std::string::npos)
      << error_of(path("loop.mat"));
}

}  // namespace
}  // namespace knoblab::interchange
