// The loop's precomputed scaling must agree with comedilib's own conversions
// (comedi_to_phys / comedi_from_phys) for linear ranges, code for code.
#include "knoblab/hal/scaling.hpp"

#include <comedilib.h>

#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace knoblab::hal {
namespace {

struct Case {
  const char* name;
  double min, max;
  std::uint32_t maxdata;
};

const Case kCases[] = {
    {"12-bit bipolar ±1.25 V", -1.25, 1.25, 4095}, {"12-bit unipolar 0–10 V", 0.0, 10.0, 4095},
    {"16-bit bipolar ±10 V", -10.0, 10.0, 65535},  {"16-bit unipolar 0–1.25 V", 0.0, 1.25, 65535},
    {"12-bit bipolar ±5 V", -5.0, 5.0, 4095},
};

class ComediScaling : public ::testing::Test {
 protected:
  void SetUp() override { comedi_set_global_oor_behavior(COMEDI_OOR_NUMBER); }  // no NaN at the rails
};

TEST_F(ComediScaling, CodeToVoltsMatchesComediToPhys) {
  for (const Case& c : kCases) {
    comedi_range rng{c.min, c.max, UNIT_volt};
    const AdcScale scale = AdcScale::from_range(c.min, c.max, c.maxdata);
    const std::uint32_t step = c.maxdata > 4095 ? 7 : 1;  // every code for 12 bit, a sweep for 16
    for (std::uint32_t raw = 0; raw <= c.maxdata; raw += step)
      ASSERT_NEAR(scale.to_volts(raw), comedi_to_phys(raw, &rng, c.maxdata), 1e-12) << c.name << " code " << raw;
    EXPECT_DOUBLE_EQ(scale.to_volts(0), c.min) << c.name;
    EXPECT_NEAR(scale.to_volts(c.maxdata), c.max, 1e-12) << c.name;
  }
}

TEST_F(ComediScaling, VoltsToCodeMatchesComediFromPhys) {
  for (const Case& c : kCases) {
    comedi_range rng{c.min, c.max, UNIT_volt};
    const DacScale scale = DacScale::from_range(c.min, c.max, c.maxdata);
    for (int i = 0; i <= 20000; ++i) {
      const double v = c.min + (c.max - c.min) * (i / 20000.0);
      ASSERT_EQ(scale.to_code(v), comedi_from_phys(v, &rng, c.maxdata)) << c.name << " at " << v << " V";
    }
  }
}

TEST(DacScale, ClampsToTheRangeAndSendsNonFiniteToZeroVolts) {
  const DacScale bipolar = DacScale::from_range(-10.0, 10.0, 4095);
  EXPECT_EQ(bipolar.to_code(25.0), 4095u);
  EXPECT_EQ(bipolar.to_code(-25.0), 0u);
  EXPECT_TRUE(bipolar.clamps(10.5));
  EXPECT_FALSE(bipolar.clamps(10.0));
  EXPECT_TRUE(bipolar.clamps(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(bipolar.to_code(std::numeric_limits<double>::quiet_NaN()), 2048u);  // 0 V
  EXPECT_EQ(bipolar.to_code(0.0), 2048u);
  const DacScale unipolar = DacScale::from_range(0.0, 10.0, 65535);
  EXPECT_EQ(unipolar.to_code(-3.0), 0u);
  EXPECT_EQ(unipolar.to_code(std::numeric_limits<double>::infinity()), 0u);  // 0 V, not full scale
}

TEST(AdcScale, FoldsGainAndOffsetIntoTheCoefficients) {
  // An external 2:1 divider in front of a ±5 V input, plus 0.1 V of offset.
  const AdcScale s = AdcScale::from_range(-5.0, 5.0, 4095, 2.0, 0.1);
  EXPECT_DOUBLE_EQ(s.to_volts(0), -9.9);
  EXPECT_NEAR(s.to_volts(4095), 10.1, 1e-12);
}

TEST(CounterUnwrap, StartsFromTheTwosComplementReading) {
  CounterUnwrap c24(0xFFFFFF);
  c24.reset(0xFFFFFF);
  EXPECT_EQ(c24.count(), -1);
  c24.reset(0x7FFFFF);
  EXPECT_EQ(c24.count(), 0x7FFFFF);
  CounterUnwrap c32(0xFFFFFFFF);
  c32.reset(0xFFFFFFF0u);
  EXPECT_EQ(c32.count(), -16);
}

TEST(CounterUnwrap, Keeps24BitCountsGoingAcrossWrapBothWays) {
  CounterUnwrap c(0xFFFFFF);
  c.reset(0xFFFFF0);
  EXPECT_EQ(c.count(), -16);
  EXPECT_EQ(c.update(0x000010), 16);  // forward through zero
  EXPECT_EQ(c.update(0xFFFFF8), -8);  // and back
  // Many turns forward at 640 000 CPR: 100 revolutions is 3.8 wraps of 2^24.
  std::int64_t expected = -8;
  std::uint32_t raw = 0xFFFFF8;
  for (int i = 0; i < 1000; ++i) {
    raw = (raw + 64000) & 0xFFFFFF;
    expected += 64000;
    ASSERT_EQ(c.update(raw), expected);
  }
  EXPECT_EQ(expected, 64'000'000 - 8);
}

TEST(CounterUnwrap, Keeps32BitCountsGoingAcrossWrap) {
  CounterUnwrap c(0xFFFFFFFF);
  c.reset(0x7FFFFFF0u);
  EXPECT_EQ(c.update(0x80000010u), 0x80000010ll);  // past INT32_MAX: no sign flip
  c.reset(0xFFFFFFFEu);
  EXPECT_EQ(c.update(0x00000003u), 3);
  EXPECT_EQ(c.update(0xFFFFFFFDu), -3);
}

TEST(CounterUnwrap, FollowsARandomWalkOfBoundedSteps) {
  for (std::uint32_t maxdata : {0xFFFFu, 0xFFFFFFu, 0xFFFFFFFFu}) {
    const std::uint64_t modulus = std::uint64_t{maxdata} + 1;
    std::mt19937_64 rng(42);
    const auto half = static_cast<std::int64_t>(modulus / 2) - 1;
    std::uniform_int_distribution<std::int64_t> step(-half, half);
    CounterUnwrap c(maxdata);
    c.reset(0);
    std::int64_t truth = 0;
    for (int i = 0; i < 10000; ++i) {
      truth += step(rng);
      const auto raw = static_cast<std::uint32_t>(static_cast<std::uint64_t>(truth) % modulus);
      ASSERT_EQ(c.update(raw), truth) << "maxdata " << maxdata << " step " << i;
    }
  }
}

}  // namespace
}  // namespace knoblab::hal
