// The SHA-256 digests that name a stored result's input: standard vectors,
// a file's bytes, and a capture's samples in the documented byte layout.
#include <gmock/gmock.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "knoblab/interchange/digest.hpp"

namespace ki = knoblab::interchange;
using ::testing::HasSubstr;

namespace {

ki::Capture two_rows(bool command) {
  ki::Capture c;
  c.has_command = command;
  c.t = {0.0, 0.001};
  c.theta = {0.5, -0.25};
  c.omega = {1.0, 2.0};
  c.alpha = {-3.0, 4.5};
  c.torque = {0.001, -0.002};
  if (command) c.command = {0.1, 0.2};
  return c;
}

using Column = std::vector<double> ki::Capture::*;
constexpr Column kColumns[] = {&ki::Capture::t,      &ki::Capture::theta,  &ki::Capture::omega,
                               &ki::Capture::alpha,  &ki::Capture::torque, &ki::Capture::command};

void put(std::string& out, std::uint64_t bits) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((bits >> (8 * i)) & 0xff);
}

}  // namespace

TEST(Digest, Sha256OfKnownBytesIsTheStandardValue) {
  EXPECT_EQ(ki::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(ki::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Digest, AFileDigestIsTheDigestOfItsBytes) {
  const auto path = std::filesystem::temp_directory_path() / ("knoblab_digest_" + std::to_string(::getpid()));
  std::string bytes(200000, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7 % 251);
  {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
  }
  EXPECT_EQ(ki::file_sha256(path), ki::sha256_hex(bytes));
  std::filesystem::remove(path);
  try {
    ki::file_sha256(path);
    FAIL() << "read a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string() + ": cannot be read"));
  }
}

TEST(Digest, SamplesDigestHashesTheDocumentedBytes) {
  for (const bool command : {false, true}) {
    ki::Capture c = two_rows(command);
    c.flags = {0, 0x15};
    std::string bytes = std::string("knoblab samples v1: t theta omega alpha torque") +
                        (command ? " command" : "") + " flags\n";
    for (std::size_t i = 0; i < 2; ++i) {
      for (const double v : {c.t[i], c.theta[i], c.omega[i], c.alpha[i], c.torque[i]})
        put(bytes, std::bit_cast<std::uint64_t>(v));
      if (command) put(bytes, std::bit_cast<std::uint64_t>(c.command[i]));
      for (int k = 0; k < 4; ++k) bytes += static_cast<char>((c.flags[i] >> (8 * k)) & 0xff);
    }
    EXPECT_EQ(ki::samples_sha256(c), ki::sha256_hex(bytes)) << "command " << command;
  }
}

TEST(Digest, SamplesDigestIgnoresMetadataAndTheSignOfZero) {
  const ki::Capture c = two_rows(true);
  ki::Capture d = c;
  d.metadata = {{"status", "incomplete"}, {"knob", "fan"}};
  d.t[0] = -0.0;
  d.flags = {0, 0};  // the same as no flags
  EXPECT_EQ(ki::samples_sha256(d), ki::samples_sha256(c));
}

TEST(Digest, SamplesDigestChangesWithAnyValueAFlagOrTheCommandColumn) {
  const ki::Capture c = two_rows(true);
  const std::string base = ki::samples_sha256(c);
  for (const Column column : kColumns) {
    ki::Capture d = c;
    (d.*column)[1] = std::nextafter((d.*column)[1], 1e9);  // one ulp
    EXPECT_NE(ki::samples_sha256(d), base);
  }
  ki::Capture flagged = c;
  flagged.flags = {0, 1};
  EXPECT_NE(ki::samples_sha256(flagged), base);
  ki::Capture no_command = c;
  no_command.has_command = false;
  no_command.command.clear();
  EXPECT_NE(ki::samples_sha256(no_command), base);
  ki::Capture shorter = c;
  for (const Column column : kColumns) (shorter.*column).pop_back();
  EXPECT_NE(ki::samples_sha256(shorter), base);
}
