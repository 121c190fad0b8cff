// The simulator's signals are plausible: skin conductance answers a stimulus
// 2–3 s late, EMG bursts within a second, the amplifier stays in its ratings.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "knoblab/modbus/sim_signals.hpp"

namespace knoblab::modbus::sim {
namespace {

constexpr double kFs = 32.0;

struct Trace {
  std::vector<double> t, corrugator, depressor, sc;
};

// 8 s at 32 Hz with one stimulus at 1 s (or none) and nothing else going on.
Trace one_stimulus(std::uint64_t seed, bool stimulus = true) {
  BiometricsModel::Params quiet;
  quiet.trial_interval_min = quiet.trial_interval_max = 0.0;
  quiet.spontaneous_scr_interval = 0.0;
  quiet.random_burst_interval = 0.0;
  BiometricsModel model(seed, quiet);
  Trace tr;
  for (int n = 1; n <= 8 * 32; ++n) {
    const double t = n / kFs;
    if (n == 32 && stimulus) model.stimulus(t);
    double c = 0, d = 0, s = 0;
    model.sample(t, c, d, s);
    tr.t.push_back(t);
    tr.corrugator.push_back(c);
    tr.depressor.push_back(d);
    tr.sc.push_back(s);
  }
  return tr;
}

double rms(const std::vector<double>& v, const std::vector<double>& t, double from, double to) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (t[i] >= from && t[i] < to) {
      sum += v[i] * v[i];
      ++n;
    }
  }
  return std::sqrt(sum / std::max(n, 1));
}

TEST(Signals, SkinConductanceRespondsTwoToThreeSecondsAfterAStimulus) {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    const Trace tr = one_stimulus(seed);
    const Trace tonic = one_stimulus(seed, false);  // same seed: the same tonic drift
    EXPECT_GT(tonic.sc[31], 1e-6);  // tonic level: µS
    EXPECT_LT(tonic.sc[31], 10e-6);
    double onset = -1, peak = 0;
    for (std::size_t i = 0; i < tr.sc.size(); ++i) {
      const double phasic = tr.sc[i] - tonic.sc[i];
      if (onset < 0 && phasic > 0.01e-6) onset = tr.t[i] - 1.0;
      peak = std::max(peak, phasic);
    }
    EXPECT_GE(onset, 2.0) << "seed " << seed;  // latency 2–3 s (+ one sample)
    EXPECT_LE(onset, 3.05) << "seed " << seed;
    EXPECT_GT(peak, 0.15e-6) << "seed " << seed;  // 0.2–1 µS responses
    EXPECT_LT(peak, 1.2e-6) << "seed " << seed;
  }
}

TEST(Signals, EmgBurstsWithinASecondOfAStimulusOnOneMuscle) {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    const Trace tr = one_stimulus(seed);
    const double rest_c = rms(tr.corrugator, tr.t, 0.0, 1.0);
    const double rest_d = rms(tr.depressor, tr.t, 0.0, 1.0);
    EXPECT_LT(rest_c, 5e-6);  // resting facial EMG: a few µV
    EXPECT_GT(rest_c, 0.5e-6);
    const double burst = std::max(rms(tr.corrugator, tr.t, 1.6, 2.4) / rest_c,
                                  rms(tr.depressor, tr.t, 1.6, 2.4) / rest_d);
    EXPECT_GT(burst, 4.0) << "seed " << seed;
  }
}

TEST(Signals, AmplifierStaysWithinItsRatings) {
  AmplifierModel amp(9);
  double t = 0, first_temp = 0;
  for (int i = 0; i < 60 * 100; ++i) {  // 60 s at 100 Hz, enabled, 1 A limit
    t += 0.01;
    const AmplifierState& s = amp.step(t, 0.01, true, 1.0);
    if (i == 0) first_temp = s.temperature;
    EXPECT_LE(std::abs(s.current), 1.0);
    EXPECT_NEAR(s.bus_voltage, 48.0, 0.5);
  }
  EXPECT_GT(amp.step(t, 0.01, true, 1.0).temperature, first_temp);  // warms under load
  EXPECT_EQ(amp.step(t + 0.01, 0.01, false, 1.0).current, 0.0);   // disabled: no current
}

}  // namespace
}  // namespace knoblab::modbus::sim
