// The biometric scores computed from the box's samples around the markers.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "knoblab/studyrun/biometric_score.hpp"

namespace knoblab::test {
namespace {

std::vector<store::BiometricSample> samples(double emg_rest, double corrugator_after, double sc_peak) {
  std::vector<store::BiometricSample> s;
  for (int i = 0; i < 32 * 6; ++i) {  // 6 s at 32 Hz; onset at 2 s
    const double t = i / 32.0;
    const double sign = i % 2 ? 1.0 : -1.0;  // a zero-mean signal of amplitude a has RMS a
    const double corr = (t >= 3.0 && t < 3.5) ? corrugator_after : emg_rest;
    const double sc = 2e-6 + (t >= 4.0 ? sc_peak : 0.0);
    s.push_back({i, t, sign * corr, sign * emg_rest, sc});
  }
  return s;
}

TEST(BiometricScore, AFrownAfterOnsetScoresNegativeValenceAsCorrugatorMinusDepressor) {
  // More corrugator than depressor is a frown: the thesis' difference trace
  // is corrugator − depressor, and its peak minus baseline is the score.
  const auto s = samples(10e-6, 40e-6, 0);
  const studyrun::BiometricScore b = studyrun::score_biometrics(s, 2.0, 5.0, 2.0);
  ASSERT_TRUE(b.emg_V);
  EXPECT_NEAR(*b.emg_V, 30e-6, 1e-6);
  EXPECT_EQ(b.baseline_samples, 64u);
}

TEST(BiometricScore, SkinConductanceIsItsPeakAfterOnsetAboveTheBaseline) {
  const auto s = samples(10e-6, 10e-6, 0.5e-6);
  const studyrun::BiometricScore b = studyrun::score_biometrics(s, 2.0, 5.0, 2.0);
  ASSERT_TRUE(b.sc_S);
  EXPECT_NEAR(*b.sc_S, 0.5e-6, 1e-12);
  EXPECT_NEAR(*b.emg_V, 0.0, 1e-9);
}

TEST(BiometricScore, WithoutABaselineThereIsNoScoreRatherThanAMadeUpOne) {
  const auto s = samples(10e-6, 40e-6, 0.5e-6);
  const studyrun::BiometricScore b = studyrun::score_biometrics(s, 0.0, 5.0, 2.0);
  EXPECT_FALSE(b.emg_V);
  EXPECT_FALSE(b.sc_S);
  EXPECT_TRUE(studyrun::to_json(b)["emg_V"].is_null());
}

}  // namespace
}  // namespace knoblab::test
