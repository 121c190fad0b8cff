// Telling the array files apart by their first bytes, not their names.
#include <gtest/gtest.h>

#include "knoblab/interchange/array_file.hpp"
#include "mat5_writer.hpp"
#include "npy_writer.hpp"

namespace knoblab::interchange {
namespace {

TEST(ArrayFile, KindComesFromTheFirstBytes) {
  EXPECT_EQ(array_file_kind(test::mat5::Writer().header()), ArrayFileKind::kMat);
  EXPECT_EQ(array_file_kind("MATLAB 7.3 MAT-file, Platform: GLNXA64"), ArrayFileKind::kMat);
  EXPECT_EQ(array_file_kind(test::npy::f8("(1,)", {1})), ArrayFileKind::kNpy);
  EXPECT_EQ(array_file_kind("\x80\x04\x95"), ArrayFileKind::kNpy);  // a pickle: the .npy reader refuses it by name
  EXPECT_EQ(array_file_kind(test::npy::zip({})), ArrayFileKind::kNpz);
  // Text is a CSV, even when its first column is called MATLAB-something.
  EXPECT_EQ(array_file_kind("MATLAB_time,angle,torque\n"), ArrayFileKind::kNone);
  EXPECT_EQ(array_file_kind("t,theta,torque\n"), ArrayFileKind::kNone);
  EXPECT_EQ(array_file_kind(""), ArrayFileKind::kNone);
}

}  // namespace
}  // namespace knoblab::interchange
