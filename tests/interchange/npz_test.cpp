// .npz reader: numpy's own np.savez and np.savez_compressed files, archives
// built here (stored and deflated members), and broken ones.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "knoblab/interchange/array_file.hpp"
#include "knoblab/interchange/npy.hpp"
#include "npy_writer.hpp"

namespace knoblab::interchange {
namespace {

namespace npy = test::npy;

std::filesystem::path reference(const std::string& name) {
  return std::filesystem::path(KNOBLAB_INTERCHANGE_REFERENCE_DIR) / "numpy" / name;
}

std::string error_of(const std::string& bytes, const MatLimits& limits = {}) {
  try {
    parse_npz(bytes, "a.npz", limits);
  } catch (const MatError& e) {
    return e.what();
  }
  return "";
}

TEST(Npz, ReadsNumpysSavezAndSavezCompressedMembersByName) {
  for (const char* name : {"two.npz", "two_compressed.npz"}) {
    auto arrays = read_array_file(reference(name));
    ASSERT_EQ(arrays.size(), 2u) << name;
    const MatArray data = take_array(arrays, "data", name);
    EXPECT_EQ(data.dims, (std::vector<std::size_t>{2, 3})) << name;
    EXPECT_EQ(data.values, (std::vector<double>{1.5, 4, -2, 5, 3e-9, 6.25})) << name;
    const MatArray t = take_array(arrays, "t", name);
    EXPECT_EQ(t.dims, (std::vector<std::size_t>{1, 3})) << name;
    EXPECT_EQ(t.values, (std::vector<double>{0, 0.5, 1})) << name;
  }
}

TEST(Npz, StoredAndDeflatedMembersBuiltHereReadAlike) {
  const std::string a = npy::f8("(3,)", {1, 2, 3}), b = npy::f8("(1, 2)", {-1, 1e300});
  for (bool deflate : {false, true}) {
    const auto arrays = parse_npz(npy::zip({{"pos.npy", a, deflate}, {"cur.npy", b, deflate}}), "a.npz");
    ASSERT_EQ(arrays.size(), 2u);
    EXPECT_EQ(arrays[0].name, "pos");
    EXPECT_EQ(arrays[0].values, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(arrays[1].name, "cur");
    EXPECT_EQ(arrays[1].values, (std::vector<double>{-1, 1e300}));
  }
}

TEST(Npz, MissingMemberListsThoseThere) {
  auto arrays = read_array_file(reference("two.npz"));
  try {
    take_array(arrays, "torque", "two.npz");
    FAIL() << "found a member that is not there";
  } catch (const MatError& e) {
    EXPECT_STREQ(e.what(), "two.npz: no variable 'torque'; the file holds data (2x3 double), t (1x3 double)");
  }
}

TEST(Npz, BrokenArchivesSayWhatIsWrong) {
  const std::string member = npy::f8("(3,)", {1, 2, 3});
  const std::string good = npy::zip({{"x.npy", member, true}});
  EXPECT_NE(error_of(good.substr(0, good.size() - 5)).find("no end-of-central-directory record"), std::string::npos);
  EXPECT_NE(error_of(npy::zip({{"x.npy", member, false}}, true)).find("member 'x.npy': CRC-32 mismatch"),
            std::string::npos);
  EXPECT_NE(error_of(npy::zip({{"notes.txt", "hello", false}})).find("member 'notes.txt' is not a .npy array"),
            std::string::npos);
  // A member whose .npy is broken: the message names the member and the byte inside it.
  const std::string broken = npy::zip({{"x.npy", member.substr(0, member.size() - 8), true}});
  EXPECT_NE(error_of(broken).find("member 'x.npy', byte 128: truncated: shape (3,)"), std::string::npos)
      << error_of(broken);
  // A member that claims to hold more than the limit is refused before it is inflated.
  MatLimits small;
  small.max_inflated_bytes = 100;
  EXPECT_NE(error_of(good, small).find("member 'x.npy' extracts to 152 bytes, over the 100-byte limit"),
            std::string::npos)
      << error_of(good, small);
  // Deflated data that does not inflate to the size its entry claims (a zip bomb's trick, or corruption).
  std::string lying = good;
  const std::size_t entry = lying.find("PK\x01\x02");
  lying[entry + 24] = static_cast<char>(lying[entry + 24] - 1);  // uncompressed size one less
  EXPECT_NE(error_of(lying).find("inflates to more than the 151 bytes its entry claims"), std::string::npos)
      << error_of(lying);
  std::string bzip2 = good;
  bzip2[entry + 10] = 12;
  EXPECT_NE(error_of(bzip2).find("compression method 12"), std::string::npos);
  std::string encrypted = good;
  encrypted[entry + 8] = 1;
  EXPECT_NE(error_of(encrypted).find("member 'x.npy' is encrypted"), std::string::npos);
  std::string many = good;
  many[many.size() - 12] = static_cast<char>(0xff);  // entry count in the end record
  EXPECT_NE(error_of(many).find("members claimed, but the central directory holds only"), std::string::npos)
      << error_of(many);
}

// Random byte flips in a good archive (and the .npy inside it): a MatError
// or a result, never a crash, never another exception.
TEST(Npz, RandomCorruptionGivesAMatErrorOrAResultNeverACrash) {
  const std::string npy_bytes = npy::f8("(2, 3)", {1, 2, 3, 4, 5, 6});
  const std::string good = npy::zip({{"a.npy", npy_bytes, false}, {"b.npy", npy::f8("(2,)", {7, 8}), true}});
  MatLimits limits;
  limits.max_inflated_bytes = 1 << 20;
  std::mt19937 rng(11);
  std::size_t refused = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::string& base = trial % 2 ? good : npy_bytes;
    std::string bytes = base;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bytes[rng() % bytes.size()] = static_cast<char>(rng() & 0xff);
    try {
      if (trial % 2) parse_npz(bytes, "a.npz", limits);
      else parse_npy(bytes, "a.npy", limits);
    } catch (const MatError&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 10000u);  // most flips break something the readers check
}

}  // namespace
}  // namespace knoblab::interchange
