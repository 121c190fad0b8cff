// MAT v5 reader: files built byte by byte here, read back; broken and hostile
// files each give a MatError that says what is wrong.
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "knoblab/interchange/mat5.hpp"
#include "mat5_writer.hpp"

namespace knoblab::interchange {
namespace {

using namespace test::mat5;

std::vector<MatArray> parse(const std::string& bytes, const MatLimits& limits = {}) {
  return parse_mat(bytes, "t.mat", limits);
}

// The message of the MatError parsing `bytes` throws ("" if it throws none).
std::string error_of(const std::string& bytes, const MatLimits& limits = {}) {
  try {
    parse(bytes, limits);
  } catch (const MatError& e) {
    return e.what();
  }
  return "";
}

// A miCOMPRESSED element holding `elements`, as MATLAB's save -v7 writes it.
std::string compressed(const Writer& w, const std::string& elements) {
  uLongf size = compressBound(static_cast<uLong>(elements.size()));
  std::string z(size, '\0');
  EXPECT_EQ(compress(reinterpret_cast<Bytef*>(z.data()), &size,
                     reinterpret_cast<const Bytef*>(elements.data()), static_cast<uLong>(elements.size())),
            Z_OK);
  z.resize(size);
  return w.tag(miCOMPRESSED, static_cast<std::uint32_t>(z.size())) + z;
}

const std::vector<double> k2x3 = {1.5, -2, 3e-9, 4, 5, 6.25};  // column-major

TEST(Mat5, DoubleMatrixValuesAndDims) {
  const Writer w;
  const auto vars = parse(w.header() + w.doubles("data", 2, 3, k2x3));
  ASSERT_EQ(vars.size(), 1u);
  const MatArray& a = vars[0];
  EXPECT_EQ(a.name, "data");
  EXPECT_EQ(a.dims, (std::vector<std::size_t>{2, 3}));
  EXPECT_TRUE(a.is_numeric());
  EXPECT_EQ(a.values, k2x3);
  EXPECT_EQ(a.at(0, 1), 3e-9);
  EXPECT_EQ(a.at(1, 2), 6.25);
  EXPECT_THROW(a.at(2, 0), std::out_of_range);
  EXPECT_EQ(a.describe(), "2x3 double");
}

TEST(Mat5, IntegerSingleAndCompactStorageConvertToDouble) {
  const Writer w;
  const std::string file =
      w.header() +
      w.matrix("i16", mxINT16, {1, 3}, w.element(miINT16, w.values<std::int16_t>({-32768, 7, 32767}))) +
      w.matrix("u8", mxUINT8, {1, 2}, w.element(miUINT8, w.values<std::uint8_t>({0, 255}))) +
      w.matrix("f32", mxSINGLE, {1, 2}, w.element(miSINGLE, w.values<float>({0.5f, -1e30f}))) +
      // MATLAB stores a double array of small integers as miUINT8.
      w.matrix("compact", mxDOUBLE, {2, 1}, w.element(miUINT8, w.values<std::uint8_t>({3, 200}))) +
      w.matrix("flag", mxUINT8, {1, 2}, w.element(miUINT8, w.values<std::uint8_t>({1, 0})), 0x0200);
  const auto v = parse(file);
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0].values, (std::vector<double>{-32768, 7, 32767}));
  EXPECT_EQ(v[1].values, (std::vector<double>{0, 255}));
  EXPECT_EQ(v[2].values, (std::vector<double>{0.5, static_cast<double>(-1e30f)}));
  EXPECT_EQ(v[3].values, (std::vector<double>{3, 200}));
  EXPECT_EQ(v[3].describe(), "2x1 double");
  EXPECT_TRUE(v[4].logical);
  EXPECT_EQ(v[4].describe(), "1x2 logical");
  EXPECT_EQ(v[4].values, (std::vector<double>{1, 0}));
}

TEST(Mat5, SmallDataElementFormat) {
  const Writer w;
  // Two int16 values fit in the tag: size 4 and type share its first word.
  const auto v = parse(w.header() +
                       w.matrix("s", mxINT16, {2, 1}, w.small_element(miINT16, w.values<std::int16_t>({-5, 9}))));
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].name, "s");
  EXPECT_EQ(v[0].values, (std::vector<double>{-5, 9}));
}

TEST(Mat5, BigEndianFileReadsTheSame) {
  const Writer w(true);
  const std::string file = w.header() + w.doubles("data", 2, 3, k2x3) +
                           w.matrix("i", mxINT16, {1, 2}, w.small_element(miINT16, w.values<std::int16_t>({-2, 300})));
  EXPECT_EQ(file.substr(126, 2), "MI");
  const auto v = parse(file);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].dims, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(v[0].values, k2x3);
  EXPECT_EQ(v[1].values, (std::vector<double>{-2, 300}));
}

TEST(Mat5, CellArraysNestAndAreColumnMajor) {
  const Writer w;
  const std::string inner = w.cell("", 1, 1, {w.doubles("", 1, 1, {42})});
  const std::string file = w.header() + w.cell("c", 2, 2,
                                               {w.doubles("", 1, 1, {0.5}), w.doubles("", 1, 3, {1, 2, 3}),
                                                inner, w.element(miMATRIX, "")});
  const auto v = parse(file);
  ASSERT_EQ(v.size(), 1u);
  const MatArray& c = v[0];
  EXPECT_TRUE(c.is_cell());
  EXPECT_EQ(c.describe(), "2x2 cell");
  ASSERT_EQ(c.cells.size(), 4u);
  EXPECT_EQ(c.cell(0, 0).values, (std::vector<double>{0.5}));
  EXPECT_EQ(c.cell(1, 0).values, (std::vector<double>{1, 2, 3}));
  EXPECT_TRUE(c.cell(0, 1).is_cell());
  EXPECT_EQ(c.cell(0, 1).cell(0, 0).values, (std::vector<double>{42}));
  EXPECT_EQ(c.cell(1, 1).numel(), 0u);  // an empty element is an empty array
}

TEST(Mat5, CompressedElementsInflate) {
  const Writer w;
  const std::string file = w.header() + compressed(w, w.doubles("data", 2, 3, k2x3)) +
                           w.doubles("plain", 1, 1, {7}) +
                           compressed(w, w.cell("c", 1, 1, {w.doubles("", 1, 2, {8, 9})}));
  const auto v = parse(file);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].values, k2x3);
  EXPECT_EQ(v[1].values, (std::vector<double>{7}));
  EXPECT_EQ(v[2].cell(0, 0).values, (std::vector<double>{8, 9}));
}

TEST(Mat5, UnsupportedClassesAreListedNotRead) {
  const Writer w;
  const std::string file =
      w.header() +
      w.matrix("s", mxSTRUCT, {1, 1}, w.small_element(miINT32, w.values<std::int32_t>({32})) + w.element(miINT8, "")) +
      w.matrix("sp", mxSPARSE, {3, 3}, "") +
      w.matrix("z", mxDOUBLE, {1, 1}, w.element(miDOUBLE, w.values<double>({1})) + w.element(miDOUBLE, w.values<double>({2})), 0x0800) +
      w.matrix("txt", mxCHAR, {1, 2}, w.small_element(miUINT16, w.values<std::uint16_t>({'h', 'i'}))) +
      w.doubles("data", 1, 1, {3});
  const auto v = parse(file);
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0].describe(), "1x1 struct");
  EXPECT_EQ(v[1].describe(), "3x3 sparse");
  EXPECT_EQ(v[2].describe(), "1x1 complex double");
  EXPECT_EQ(v[3].describe(), "1x2 char");
  for (int i = 0; i < 4; ++i) EXPECT_FALSE(v[static_cast<std::size_t>(i)].is_numeric()) << i;
  EXPECT_EQ(v[4].values, (std::vector<double>{3}));
}

TEST(Mat5, ReadFromFileAndMissingVariableListsTheNames) {
  const Writer w;
  const auto path = std::filesystem::temp_directory_path() /
                    ("knoblab_mat5_test_" + std::to_string(std::random_device{}()) + ".mat");
  {
    std::ofstream out(path, std::ios::binary);
    out << w.header() << w.doubles("data", 2, 3, k2x3) << compressed(w, w.cell("c", 1, 1, {w.doubles("", 1, 1, {1})}));
  }
  EXPECT_EQ(read_mat(path).size(), 2u);
  EXPECT_EQ(read_mat_variable(path, "data").values, k2x3);
  try {
    read_mat_variable(path, "position");
    ADD_FAILURE() << "no MatError";
  } catch (const MatError& e) {
    EXPECT_NE(std::string(e.what()).find("no variable 'position'; the file holds data (2x3 double), c (1x1 cell)"),
              std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
  EXPECT_THROW(read_mat(path), MatError);  // missing file
}

// ---- broken and hostile files ----------------------------------------------

TEST(Mat5Hostile, TruncatedAnywhereIsAClearError) {
  const Writer w;
  for (const std::string& var : {w.doubles("data", 2, 3, k2x3), compressed(w, w.doubles("data", 2, 3, k2x3)),
                                 w.cell("c", 1, 2, {w.doubles("", 1, 1, {1}), w.doubles("", 1, 2, {2, 3})})}) {
    const std::string file = w.header() + var;
    ASSERT_EQ(parse(file).size(), 1u);
    for (std::size_t cut = 0; cut < file.size(); ++cut) {
      if (cut == 128) continue;  // the header alone is a valid file with no variables
      const std::string msg = error_of(file.substr(0, cut));
      const bool clear = msg.find("truncated") != std::string::npos ||
                         msg.find("runs past the end") != std::string::npos ||
                         msg.find("not a MAT v5 file") != std::string::npos;
      EXPECT_TRUE(clear) << "cut at " << cut << ": '" << msg << "'";
    }
  }
  EXPECT_EQ(error_of(w.header().substr(0, 100)), "t.mat: offset 100: truncated: the header needs 128 bytes, the file has 100");
  EXPECT_EQ(error_of(w.header() + w.doubles("data", 1, 1, {1}).substr(0, 30)),
            "t.mat: offset 128: element of 56 bytes runs past the end of its container (22 bytes left)");
}

TEST(Mat5Hostile, ZlibStreamThatStopsShortIsTruncated) {
  const Writer w;
  const std::string whole = compressed(w, w.doubles("data", 2, 3, k2x3));
  const std::string stream = whole.substr(8, whole.size() - 8 - 10);  // 10 bytes short, tag agrees
  const std::string msg =
      error_of(w.header() + w.tag(miCOMPRESSED, static_cast<std::uint32_t>(stream.size())) + stream);
  EXPECT_NE(msg.find("offset 128: compressed element is truncated"), std::string::npos) << msg;
}

TEST(Mat5Hostile, OversizedElementLength) {
  const Writer w;
  const std::string msg = error_of(w.header() + w.tag(miMATRIX, 0x7fffffff) + std::string(64, '\0'));
  EXPECT_NE(msg.find("offset 128: element of 2147483647 bytes runs past the end"), std::string::npos) << msg;
  // Inside a matrix: the name claims more than the matrix holds.
  std::string m = w.element(miUINT32, w.uint(mxDOUBLE, 4) + w.uint(0, 4)) +
                  w.element(miINT32, w.values<std::int32_t>({1, 1})) + w.tag(miINT8, 1000);
  EXPECT_NE(error_of(w.header() + w.element(miMATRIX, m)).find("element of 1000 bytes runs past the end"),
            std::string::npos);
  EXPECT_NE(error_of(w.header() + w.uint(0x00080001, 4) + "abcd").find("small data element claims 8 bytes"),
            std::string::npos);
}

TEST(Mat5Hostile, DimsThatOverflowOrExceedTheData) {
  const Writer w;
  const std::int32_t big = 0x7fffffff;
  std::string msg = error_of(w.header() + w.matrix("x", mxDOUBLE, {big, big, big}, w.element(miDOUBLE, "")));
  EXPECT_NE(msg.find("dimensions overflow"), std::string::npos) << msg;
  msg = error_of(w.header() + w.matrix("x", mxDOUBLE, {1000, 1000}, w.element(miDOUBLE, w.values<double>({1, 2, 3}))));
  EXPECT_NE(msg.find("dimensions say 1000000 elements, the data holds 24 bytes"), std::string::npos) << msg;
  msg = error_of(w.header() + w.matrix("c", mxCELL, {100000, 100000}, ""));
  EXPECT_NE(msg.find("cell array of 10000000000 cells, but only 0 bytes hold them"), std::string::npos) << msg;
  msg = error_of(w.header() + w.matrix("x", mxDOUBLE, {-1, 2}, ""));
  EXPECT_NE(msg.find("negative dimension -1"), std::string::npos) << msg;
}

TEST(Mat5Hostile, DeepNestingIsCapped) {
  const Writer w;
  std::string inner = w.doubles("", 1, 1, {1});
  for (int i = 0; i < 100; ++i) inner = w.cell("", 1, 1, {inner});
  const std::string msg = error_of(w.header() + w.cell("deep", 1, 1, {inner}));
  EXPECT_NE(msg.find("arrays nested deeper than 32 levels"), std::string::npos) << msg;
  // Just under the cap is fine.
  std::string ok = w.doubles("", 1, 1, {1});
  for (int i = 0; i < 31; ++i) ok = w.cell("", 1, 1, {ok});
  EXPECT_NO_THROW(parse(w.header() + w.cell("ok", 1, 1, {ok})));
}

TEST(Mat5Hostile, ZlibBombStopsAtTheInflateCap) {
  const Writer w;
  // 8 MiB of zeros compress to a few KiB.
  const std::string bomb = compressed(w, w.doubles("z", 1024, 1024, std::vector<double>(1024 * 1024, 0.0)));
  ASSERT_LT(bomb.size(), 64u * 1024);
  MatLimits limits;
  limits.max_inflated_bytes = 1 << 20;
  const std::string msg = error_of(w.header() + bomb, limits);
  EXPECT_NE(msg.find("offset 128: compressed element inflates to more than 1048576 bytes (the limit)"),
            std::string::npos) << msg;
  // Within the default cap the same element reads.
  EXPECT_EQ(parse(w.header() + bomb).at(0).values.size(), 1024u * 1024);
}

TEST(Mat5Hostile, CorruptCompressedDataAndNestedCompression) {
  const Writer w;
  std::string msg = error_of(w.header() + w.tag(miCOMPRESSED, 16) + std::string(16, '\x55'));
  EXPECT_NE(msg.find("compressed element is corrupt: zlib says"), std::string::npos) << msg;
  msg = error_of(w.header() + compressed(w, compressed(w, w.doubles("x", 1, 1, {1}))));
  EXPECT_NE(msg.find("in compressed element, inflated byte 0: compressed element inside a compressed element"),
            std::string::npos) << msg;
}

TEST(Mat5Hostile, NotAMatFile) {
  EXPECT_EQ(error_of("t,theta,torque\n0,0,0\n1,1,1\n2,2,2\n"),
            "t.mat: not a MAT v5 file: it does not start with the 'MATLAB 5.0 MAT-file' header text "
            "(MAT v4 files are not supported either)");
  EXPECT_NE(error_of("").find("not a MAT v5 file"), std::string::npos);
  std::string bad_endian = Writer().header();
  bad_endian[126] = 'X';
  EXPECT_NE(error_of(bad_endian).find("offset 126: bad endian indicator"), std::string::npos);
  const Writer w;
  const std::string text = w.header() + w.tag(miINT8, 3) + "abc" + std::string(5, '\0');
  EXPECT_NE(error_of(text).find("top-level element of type 1"), std::string::npos);
}

TEST(Mat5Hostile, Version73HeaderWithBrokenHdf5IsRefusedByTheHdf5Reader) {
  // What MATLAB's save -v7.3 writes: a text header as userblock, HDF5 at 512
  // (here only its signature: mat73_test.cpp reads whole files).
  std::string v73 = "MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Jan 27 2020 HDF5 schema 1.00 .";
  v73.resize(512, ' ');
  v73 += std::string("\x89HDF\r\n\x1a\n", 8) + std::string(64, '\0');
  const std::string msg = error_of(v73);
  EXPECT_NE(msg.find("t.mat: MAT v7.3: not a readable HDF5 file"), std::string::npos) << msg;
  // The HDF5 signature alone is enough to go there.
  std::string h5 = Writer().header();
  h5.resize(512, '\0');
  h5 += std::string("\x89HDF\r\n\x1a\n", 8);
  EXPECT_NE(error_of(h5).find("MAT v7.3: not a readable HDF5 file"), std::string::npos);
  // A v5 header claiming version 0x0200 with no HDF5 behind it.
  std::string claimed = Writer().header();
  claimed[124] = 0;
  claimed[125] = 2;
  EXPECT_NE(error_of(claimed).find("the header says MAT v7.3, but no HDF5 data follows it at byte 512"),
            std::string::npos);
}

// Random byte flips in good files: a MatError or a result, never a crash,
// never another exception.
TEST(Mat5Hostile, RandomCorruptionNeverCrashes) {
  const Writer w;
  const std::string good =
      w.header() + w.doubles("data", 2, 3, k2x3) +
      w.cell("c", 1, 2, {w.doubles("", 1, 1, {1}), w.matrix("", mxINT16, {1, 2}, w.small_element(miINT16, w.values<std::int16_t>({1, 2})))}) +
      compressed(w, w.doubles("z", 1, 3, {1, 2, 3}));
  MatLimits limits;
  limits.max_inflated_bytes = 1 << 20;
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20000; ++trial) {
    std::string bytes = good;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f)
      bytes[rng() % bytes.size()] = static_cast<char>(rng() & 0xff);
    try {
      parse(bytes, limits);
    } catch (const MatError&) {
    }
  }
}

}  // namespace
}  // namespace knoblab::interchange
