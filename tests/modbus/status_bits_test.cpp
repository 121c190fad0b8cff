// The status word's bits: which problems stop torque, which only spoil a
// recording, and the names logs print for them.
#include <gtest/gtest.h>

#include <bit>
#include <set>
#include <string>

#include "knoblab/modbus/status_bits.hpp"

namespace knoblab::modbus::status {
namespace {

TEST(StatusBits, NoBiometricsProblemIsInTheAmpTripMask) {
  for (const std::uint32_t bit : {kBiometricsLost, kBiometricsStale, kBiometricsException, kBiometricsMismatch}) {
    EXPECT_NE(kBiometricsMask & bit, 0u) << describe(bit);
    EXPECT_NE(kProblemMask & bit, 0u) << describe(bit) << " is a problem";
    EXPECT_EQ(kAmpTripMask & bit, 0u) << describe(bit) << " would cut torque";
  }
  for (const std::uint32_t bit : {kAmpFault, kAmpCommsLost, kAmpDisabledUnexpectedly, kAmpMismatch})
    EXPECT_NE(kAmpTripMask & bit, 0u) << describe(bit) << " must cut torque";
  EXPECT_EQ(kAmpTripMask & ~kProblemMask, 0u);
}

TEST(StatusBits, EachBitHasItsOwnPositionAndName) {
  const std::uint32_t bits[] = {kAmpFault, kAmpCommsLost, kAmpDisabledUnexpectedly, kBiometricsLost,
                                kBiometricsStale, kAmpException, kBiometricsException, kAmpMismatch,
                                kBiometricsMismatch, kAmpEnabled, kRunning};
  std::uint32_t all = 0;
  std::set<std::string> names;
  for (const std::uint32_t bit : bits) {
    EXPECT_EQ(std::popcount(bit), 1);
    EXPECT_EQ(all & bit, 0u) << describe(bit) << " shares a position";
    all |= bit;
    const std::string name = describe(bit);
    EXPECT_EQ(name.find('|'), std::string::npos) << name;
    EXPECT_NE(name, "ok");
    EXPECT_TRUE(names.insert(name).second) << name << " twice";
  }
  EXPECT_EQ(kProblemMask & (kAmpEnabled | kRunning), 0u);  // state, not problems
  EXPECT_EQ(describe(kAmpMismatch | kBiometricsMismatch), "amp-mismatch|biometrics-mismatch");
  EXPECT_EQ(describe(0), "ok");
}

}  // namespace
}  // namespace knoblab::modbus::status
