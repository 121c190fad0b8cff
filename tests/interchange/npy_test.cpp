// .npy reader: files numpy itself wrote (tests/reference/numpy), files built
// byte by byte here, and hostile ones that must each be refused saying why.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "knoblab/interchange/array_file.hpp"
#include "knoblab/interchange/npy.hpp"
#include "npy_writer.hpp"

namespace knoblab::interchange {
namespace {

namespace npy = test::npy;

std::filesystem::path reference(const std::string& name) {
  return std::filesystem::path(KNOBLAB_INTERCHANGE_REFERENCE_DIR) / "numpy" / name;
}

// The generator's M = [[1.5, -2, 3e-9], [4, 5, 6.25]], column-major as MatArray holds it.
const std::vector<double> kM = {1.5, 4, -2, 5, 3e-9, 6.25};

std::string error_of(const std::string& bytes, const MatLimits& limits = {}) {
  try {
    parse_npy(bytes, "a.npy", limits);
  } catch (const MatError& e) {
    return e.what();
  }
  return "";
}

TEST(Npy, ReadsWhatNumpyWroteInEitherOrderAndByteOrder) {
  for (const char* name : {"m_f8.npy", "m_f8_fortran_be.npy"}) {
    const auto arrays = read_array_file(reference(name));
    ASSERT_EQ(arrays.size(), 1u) << name;
    const MatArray& a = arrays[0];
    EXPECT_EQ(a.name, std::filesystem::path(name).stem().string());
    EXPECT_EQ(a.dims, (std::vector<std::size_t>{2, 3})) << name;
    EXPECT_EQ(a.values, kM) << name;
    EXPECT_EQ(a.at(0, 1), -2) << name;  // numpy's M[0, 1]
    EXPECT_EQ(a.describe(), "2x3 double");
  }
}

TEST(Npy, ReadsIntegerBoolAndSingleDtypesAndFormatVersions2And3) {
  const MatArray i2 = read_array_file(reference("i_i2_be.npy"))[0];
  EXPECT_EQ(i2.describe(), "2x3 int16");
  EXPECT_EQ(i2.values, (std::vector<double>{1, 4, -2, 5, 3, -32768}));
  const MatArray u1 = read_array_file(reference("i_u1_fortran.npy"))[0];
  EXPECT_EQ(u1.describe(), "2x2 uint8");
  EXPECT_EQ(u1.values, (std::vector<double>{1, 4, 2, 5}));
  const MatArray b = read_array_file(reference("b_bool.npy"))[0];
  EXPECT_EQ(b.describe(), "2x3 logical");
  EXPECT_EQ(b.values, (std::vector<double>{1, 1, 0, 1, 0, 1}));
  const MatArray f4 = read_array_file(reference("m_f4_v2.npy"))[0];
  EXPECT_EQ(f4.describe(), "2x3 single");
  for (std::size_t i = 0; i < kM.size(); ++i) EXPECT_EQ(f4.values[i], static_cast<double>(static_cast<float>(kM[i])));
  const MatArray i8 = read_array_file(reference("m_i8_v3.npy"))[0];
  EXPECT_EQ(i8.describe(), "2x3 int64");
  EXPECT_EQ(i8.values, (std::vector<double>{1, 4, -2, 5, 3, -32768}));
}

TEST(Npy, OneDimensionalArrayIsARowAsSavematMakesIt) {
  const MatArray row = read_array_file(reference("row_f8.npy"))[0];
  EXPECT_EQ(row.dims, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(row.values, (std::vector<double>{4, 5, 6.25}));
  const MatArray scalar = parse_npy(npy::f8("()", {7}), "s.npy");
  EXPECT_EQ(scalar.dims, (std::vector<std::size_t>{1, 1}));
  EXPECT_EQ(scalar.values, (std::vector<double>{7}));
}

TEST(Npy, BuiltHereBigEndianFortranInt32AndPython2LongShapes) {
  const std::string bytes =
      npy::preamble(npy::header(">i4", "(2L, 2L)", true)) + npy::data({-1, 2, 70000, -70000}, 4, false, true);
  const MatArray a = parse_npy(bytes, "a.npy");
  EXPECT_EQ(a.describe(), "2x2 int32");
  EXPECT_EQ(a.values, (std::vector<double>{-1, 2, 70000, -70000}));  // Fortran order is MatArray's order
}

TEST(Npy, PicklesAndObjectArraysAreNeverLoaded) {
  for (const char* name : {"object.npy", "pickle.npy"}) {
    try {
      read_array_file(reference(name));
      ADD_FAILURE() << name << " was read";
    } catch (const MatError& e) {
      EXPECT_NE(std::string(e.what()).find("pickle"), std::string::npos) << e.what();
    }
  }
}

struct Hostile {
  std::string what;
  std::string bytes;
  std::string message;
};

TEST(Npy, BrokenAndHostileFilesSayWhatIsWrong) {
  const std::string good = npy::f8("(2, 3)", kM);
  const std::vector<Hostile> cases = {
      {"data cut short", good.substr(0, good.size() - 8),
       "a.npy: offset 128: truncated: shape (2, 3) of 8-byte values needs 48 bytes, the file holds 40 after its header"},
      {"header cut short", good.substr(0, 30), "truncated: the header claims 118 bytes, 20 follow"},
      {"not numpy", "t,theta,torque\n", "a.npy: not a .npy file"},
      {"version 4", std::string("\x93NUMPY\x04\x00", 8) + good.substr(8), "unsupported .npy format version 4.0"},
      {"huge shape", npy::f8("(1000000, 1000000)", {}), "needs 8000000000000 bytes, the file holds 0"},
      {"shape beyond 64 bits", npy::f8("(4000000000, 4000000000)", {}), "needs more than 2^64 bytes"},
      {"shape overflowing", npy::f8("(100000000000, 100000000000)", {}), "overflows 64 bits"},
      {"dimension overflowing", npy::f8("(99999999999999999999999,)", {}), "a dimension does not fit in 64 bits"},
      {"object dtype", npy::preamble(npy::header("|O", "(1,)")) + "\x80\x04", "object array (dtype '|O')"},
      {"structured dtype", npy::preamble("{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (1,), }"),
       "structured dtype"},
      {"complex", npy::preamble(npy::header("<c16", "(1,)")) + std::string(16, '\0'), "complex array"},
      {"float16", npy::preamble(npy::header("<f2", "(1,)")) + std::string(2, '\0'), "unsupported dtype '<f2'"},
      {"text dtype", npy::preamble(npy::header("<U3", "(1,)")) + std::string(12, '\0'), "holds text"},
      {"three dimensions", npy::f8("(1, 1, 1)", {1}), "array of shape (1, 1, 1): knoblab reads 1-D and 2-D arrays"},
      {"code in the header", npy::preamble("{'descr': __import__('os').system('true'), 'shape': (1,), }"),
       "header: expected a quoted string, found '_'"},
      {"unknown key", npy::preamble("{'descr': '<f8', 'fortran_order': False, 'shape': (1,), 'x': 1, }"),
       "unknown header key 'x'"},
      {"missing shape", npy::preamble("{'descr': '<f8', 'fortran_order': False, }"), "missing key 'shape'"},
      {"bad fortran_order", npy::preamble("{'descr': '<f8', 'fortran_order': 1, 'shape': (1,), }"),
       "'fortran_order': expected True or False"},
      {"control byte", npy::preamble(std::string("{'descr': '<f8'\x01, }")), "header: byte 1 cannot be in a version 1.0 header"},
      {"two arrays in one file", good + good, "bytes follow the array's data (several arrays saved into one file?)"},
  };
  for (const auto& c : cases) {
    const std::string message = error_of(c.bytes);
    EXPECT_NE(message.find(c.message), std::string::npos) << c.what << ": " << message;
  }
  MatLimits small;
  small.max_inflated_bytes = 40;
  EXPECT_NE(error_of(good, small).find("array of 6 values is over the 40-byte limit"), std::string::npos);
}

}  // namespace
}  // namespace knoblab::interchange
