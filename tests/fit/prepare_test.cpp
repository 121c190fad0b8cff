// prepare(): Table 6 filtering, derived ω and α, flagged samples left out.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/model/trajectory.hpp"

namespace knoblab::fit {
namespace {

constexpr double kPi = std::numbers::pi;

// Table 3's spatial sweep at `rate` Hz; torque carries a 2 kHz hum on top of
// a slow signal, and α a constant offset only the accelerometer has.
interchange::Capture sweep_capture(double rate, double seconds = 2.0) {
  const model::SweptSine sweep = model::SweptSine::spatial();
  interchange::Capture c;
  for (int n = 0; n < static_cast<int>(seconds * rate); ++n) {
    const double t = n / rate;
    const auto k = sweep.at(t);
    c.t.push_back(t);
    c.theta.push_back(k.theta);
    c.omega.push_back(0.0);  // a causal estimate the fit must not use
    c.alpha.push_back(k.alpha + 5.0);
    c.torque.push_back(0.01 * std::sin(2 * kPi * 3 * t) + 0.002 * std::sin(2 * kPi * 2000 * t));
  }
  return c;
}

double rms_between(const std::vector<double>& a, const std::vector<double>& b, std::size_t skip) {
  double s = 0;
  for (std::size_t i = skip; i < a.size() - skip; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / static_cast<double>(a.size() - 2 * skip));
}

TEST(Prepare, TableSixFilterRemovesTheHumAndKeepsTheSignalInPhase) {
  const interchange::Capture c = sweep_capture(10000);
  const FitData d = prepare(c);
  EXPECT_NEAR(d.rate_hz, 10000, 1e-6);
  std::vector<double> slow(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) slow[i] = 0.01 * std::sin(2 * kPi * 3 * c.t[i]);
  // 2 kHz is beyond the 500 Hz stop edge (≥ 20 dB down, twice over with
  // forward–backward), and zero phase leaves the 3 Hz signal where it was.
  EXPECT_LT(rms_between(d.torque, slow, 100), 0.0002);
  PrepOptions raw;
  raw.filter = false;
  EXPECT_GT(rms_between(prepare(c, raw).torque, slow, 100), 0.001);
  // The torque as recorded rides along, hum and all (a clipped sensor's flat
  // tops are seen there, not after the filter's ringing).
  ASSERT_EQ(d.torque_recorded.size(), d.size());
  EXPECT_EQ(d.torque_recorded, c.torque);
}

TEST(Prepare, VelocityFromTheEncoderAccelerationFromTheAccelerometerByDefault) {
  const interchange::Capture c = sweep_capture(5000);
  PrepOptions encoder;
  encoder.alpha = AlphaSource::Encoder;
  const FitData d = prepare(c, encoder);
  const model::SweptSine sweep = model::SweptSine::spatial();
  double worst_w = 0, worst_a = 0;
  for (std::size_t i = 200; i < d.size() - 200; ++i) {
    worst_w = std::max(worst_w, std::abs(d.omega[i] - sweep.omega(d.t[i])));
    worst_a = std::max(worst_a, std::abs(d.alpha[i] - sweep.alpha(d.t[i])));
  }
  EXPECT_LT(worst_w, 1e-4);
  EXPECT_LT(worst_a, 1e-2);  // not the accelerometer's +5 offset

  // The default reads the α column (the capture's accelerometer, +5 here).
  const FitData da = prepare(c);
  EXPECT_NEAR(da.alpha[d.size() / 2] - sweep.alpha(da.t[d.size() / 2]), 5.0, 0.01);
  EXPECT_NEAR(da.omega[d.size() / 2], d.omega[d.size() / 2], 1e-12);

  interchange::Capture derived = c;
  derived.alpha_derived = true;  // the CSV had no α: the encoder it is
  EXPECT_NEAR(prepare(derived).alpha[d.size() / 2], d.alpha[d.size() / 2], 1e-12);
}

TEST(Prepare, FlaggedSamplesAreFilteredWithTheRestThenLeftOut) {
  interchange::Capture c = sweep_capture(5000);
  c.flags.assign(c.size(), interchange::kAmpEnabled);
  for (std::size_t i = 3000; i < 3500; ++i) c.flags[i] |= interchange::kFaultLatched;
  c.flags[100] |= interchange::kTorqueLimited;
  const FitData d = prepare(c);
  EXPECT_EQ(d.size(), c.size() - 501);
  EXPECT_EQ(d.t[100], c.t[101]);
  EXPECT_EQ(d.t[2999], c.t[3000 + 500]);
  EXPECT_EQ(d.torque_recorded[2999], c.torque[3000 + 500]);
}

TEST(Prepare, RejectsDataAFitCannotUse) {
  interchange::Capture c = sweep_capture(5000);
  interchange::Capture short_c = c;
  for (auto* v : {&short_c.t, &short_c.theta, &short_c.omega, &short_c.alpha, &short_c.torque}) v->resize(50);
  EXPECT_THROW(prepare(short_c), FitDataError);

  interchange::Capture backwards = c;
  backwards.t[10] = backwards.t[9];
  EXPECT_THROW(prepare(backwards), FitDataError);

  interchange::Capture nan = c;
  nan.torque[7] = std::nan("");
  EXPECT_THROW(prepare(nan), FitDataError);

  interchange::Capture still = c;
  std::fill(still.theta.begin(), still.theta.end(), 0.3);
  EXPECT_THROW(prepare(still), FitDataError);

  interchange::Capture all_flagged = c;
  all_flagged.flags.assign(c.size(), interchange::kEstopActive);
  EXPECT_THROW(prepare(all_flagged), FitDataError);
}

}  // namespace
}  // namespace knoblab::fit
