// The realtime side of the filters: streaming SOS, state resets, box filter,
// and the zero-phase property of sosfiltfilt.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <type_traits>
#include <vector>

#include "knoblab/model/filters.hpp"

namespace knoblab::model {
namespace {

// Inline storage only: copying a cascade (e.g. into the render loop) cannot
// touch the heap.
static_assert(std::is_trivially_copyable_v<SosCascade>);
static_assert(std::is_trivially_copyable_v<BoxFilter3>);
static_assert(noexcept(std::declval<SosCascade&>().process(0.0)));
static_assert(noexcept(std::declval<BoxFilter3&>().process(0.0)));

std::vector<double> test_signal(std::size_t n) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double k = static_cast<double>(i);
    x[i] = 0.4 + std::sin(0.01 * k) + 0.3 * std::sin(1.3 * k) + (i > n / 2 ? 0.5 : 0.0);
  }
  return x;
}

TEST(SosCascade, StreamingEqualsOfflineSosfilt) {
  SosCascade f = design_butterworth_lowpass(10, 1000.0, 10000.0);
  const std::vector<double> x = test_signal(500);
  const std::vector<double> offline = sosfilt(f, x);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_DOUBLE_EQ(f.process(x[i]), offline[i]);
  // After reset the same again.
  f.reset();
  EXPECT_DOUBLE_EQ(f.process(x[0]), offline[0]);
}

TEST(SosCascade, SteadyStateStartIsBumpless) {
  for (const SosCascade& design : {design_butterworth_lowpass(10, 1000.0, 10000.0),
                                   design_butterworth_lowpass(5, 300.0, 10000.0),
                                   design_cheby2_lowpass(3, 20.0, 500.0, 5000.0)}) {
    SosCascade f = design;
    f.reset_to_steady_state(2.5);
    for (int i = 0; i < 200; ++i) EXPECT_NEAR(f.process(2.5), 2.5, 1e-12);
  }
}

TEST(SosCascade, ZeroStateStartRisesFromZero) {
  SosCascade f = design_butterworth_lowpass(4, 100.0, 10000.0);
  EXPECT_LT(std::abs(f.process(1.0)), 1e-3);
  for (int i = 0; i < 5000; ++i) f.process(1.0);
  EXPECT_NEAR(f.process(1.0), 1.0, 1e-9);
}

TEST(SosCascade, RejectsTooManySections) {
  const std::vector<Sos> eleven(11);
  EXPECT_THROW(SosCascade{eleven}, std::invalid_argument);
  const std::vector<Sos> ten(10);
  EXPECT_EQ(SosCascade{ten}.size(), 10u);
}

TEST(SosCascade, EmptyCascadePassesThrough) {
  SosCascade f;
  EXPECT_EQ(f.process(3.0), 3.0);
  EXPECT_EQ(f.dc_gain(), 1.0);
}

TEST(Sosfiltfilt, IsZeroPhaseWithSquaredMagnitude) {
  const double fs = 5000.0, f0 = 300.0;
  const SosCascade f = design_cheby2_lowpass(3, 20.0, 1000.0, fs);
  std::vector<double> x(4000);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = std::sin(2.0 * std::numbers::pi * f0 * static_cast<double>(i) / fs);
  const std::vector<double> y = sosfiltfilt(f, x);
  const double gain = std::norm(f.response(f0, fs));  // |H|²
  for (std::size_t i = 1000; i < 3000; ++i) EXPECT_NEAR(y[i], gain * x[i], 1e-6);
}

TEST(Sosfiltfilt, NeedsInputLongerThanPadding) {
  const SosCascade f = design_butterworth_lowpass(3, 1000.0, 10000.0);  // padlen 12
  EXPECT_THROW(sosfiltfilt(f, std::vector<double>(12, 1.0)), std::invalid_argument);
  EXPECT_EQ(sosfiltfilt(f, std::vector<double>(13, 1.0)).size(), 13u);
}

TEST(Sosfiltfilt, ConstantInputComesOutUnchanged) {
  const SosCascade f = design_butterworth_lowpass(10, 1000.0, 10000.0);
  for (double v : sosfiltfilt(f, std::vector<double>(200, -0.75))) EXPECT_NEAR(v, -0.75, 1e-12);
}

TEST(BoxFilter3, IsTheMeanOfTheLastThreeSamples) {
  BoxFilter3 box;
  EXPECT_DOUBLE_EQ(box.process(3.0), 1.0);  // history starts at zero
  EXPECT_DOUBLE_EQ(box.process(6.0), 3.0);
  EXPECT_DOUBLE_EQ(box.process(9.0), 6.0);
  EXPECT_DOUBLE_EQ(box.process(0.0), 5.0);
  box.reset();
  EXPECT_DOUBLE_EQ(box.process(0.0), 0.0);
  box.reset_to_steady_state(4.0);
  EXPECT_DOUBLE_EQ(box.process(4.0), 4.0);
  EXPECT_DOUBLE_EQ(box.process(1.0), 3.0);
}

}  // namespace
}  // namespace knoblab::model
