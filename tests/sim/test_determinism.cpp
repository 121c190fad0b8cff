#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"

using namespace knoblab::sim;

namespace {

struct Recording {
  std::vector<SensorReadings> readings;
  std::vector<PlantState> states;
};

Recording run(std::uint64_t seed) {
  PlantConfig cfg;
  cfg.knob = *presets::knob("moderate-detents");
  cfg.seed = seed;
  Plant p(cfg);
  Recording r;
  const double dt = 1e-4;
  for (int n = 0; n < 20000; ++n) {
    const double t = n * dt;
    p.step(4.0 * std::sin(2 * std::numbers::pi * (1.0 + t) * t), dt);
    r.readings.push_back(p.readings());
    r.states.push_back(p.state());
  }
  return r;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(Determinism, SameSeedIsBitIdentical) {
  const Recording a = run(42), b = run(42);
  ASSERT_EQ(a.readings.size(), b.readings.size());
  for (std::size_t i = 0; i < a.readings.size(); ++i) {
    ASSERT_EQ(a.readings[i].encoder_counts, b.readings[i].encoder_counts) << i;
    ASSERT_TRUE(same_bits(a.readings[i].torque_volts, b.readings[i].torque_volts)) << i;
    ASSERT_TRUE(same_bits(a.readings[i].accel_volts, b.readings[i].accel_volts)) << i;
    ASSERT_TRUE(same_bits(a.states[i].knob_angle, b.states[i].knob_angle)) << i;
  }
  // The run is not trivial: the knob crossed several detents.
  EXPECT_GT(std::abs(a.states.back().knob_angle) + std::abs(a.states[10000].knob_angle), 0.0);
  double travel = 0;
  for (const auto& s : a.states) travel = std::max(travel, std::abs(s.knob_angle));
  EXPECT_GT(travel, 0.6);
}

TEST(Determinism, SeedsDifferOnlyInNoise) {
  const Recording a = run(1), b = run(2);
  int torque_diff = 0, accel_diff = 0;
  for (std::size_t i = 0; i < a.readings.size(); ++i) {
    // The physics never sees the noise.
    ASSERT_TRUE(same_bits(a.states[i].knob_angle, b.states[i].knob_angle)) << i;
    ASSERT_TRUE(same_bits(a.states[i].coupling_torque, b.states[i].coupling_torque)) << i;
    ASSERT_TRUE(same_bits(a.states[i].current, b.states[i].current)) << i;
    ASSERT_EQ(a.readings[i].encoder_counts, b.readings[i].encoder_counts) << i;
    torque_diff += a.readings[i].torque_volts != b.readings[i].torque_volts;
    accel_diff += a.readings[i].accel_volts != b.readings[i].accel_volts;
    // …and the noise is small: a few σ at most.
    ASSERT_NEAR(a.readings[i].torque, b.readings[i].torque, 0.6e-3) << i;
  }
  EXPECT_GT(torque_diff, 15000);
  EXPECT_GT(accel_diff, 15000);
}

TEST(Determinism, ResetReplaysTheSameRun) {
  PlantConfig cfg;
  cfg.knob = *presets::knob("subtle-detents");
  Plant p(cfg);
  std::vector<double> first;
  for (int n = 0; n < 3000; ++n) first.push_back(p.step(2.0, 1e-4).torque_volts);
  p.reset();
  for (int n = 0; n < 3000; ++n) ASSERT_TRUE(same_bits(first[n], p.step(2.0, 1e-4).torque_volts)) << n;
}

TEST(Determinism, SubstepsFollowTheLoopRate) {
  // 10 kHz → 10 substeps of 10 µs; 1 kHz → 100 substeps of 10 µs: both
  // integrate the same physics, so a slow move ends in the same place.
  PlantConfig cfg;
  cfg.knob = *presets::knob("high-inertia");
  Plant fast(cfg), slow(cfg);
  for (int n = 0; n < 5000; ++n) fast.step(3.0, 1e-4);
  for (int n = 0; n < 500; ++n) slow.step(3.0, 1e-3);
  EXPECT_NEAR(fast.state().t, 0.5, 1e-12);
  EXPECT_NEAR(slow.state().knob_angle, fast.state().knob_angle,
              1e-6 * std::abs(fast.state().knob_angle) + 1e-9);
}
