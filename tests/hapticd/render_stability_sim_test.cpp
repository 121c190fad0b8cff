// The stability bound (model/render_stability.hpp) against the simulated
// plant: hapticd's core in simulated time on the sim DAQ (amplifier, motor,
// gripper coupling, knob, encoder), the knob held by the sim's hand with the
// grip the bound assumes, displaced and released to a stiff spring tile. The
// bound is only as real as its agreement with this.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core_harness.hpp"
#include "knoblab/hapticd/render_controller.hpp"
#include "knoblab/model/render_stability.hpp"
#include "knoblab/sim/hand.hpp"

namespace knoblab::hapticd {
namespace {

constexpr double kDisplacement = 0.2e-3;  // rad: 20 encoder counts; K·θ within the torque limit up to 900 N·m/rad

// The haptic device held by the default hand (kGripStiffness, kGripDamping),
// at rest at the hand, nothing else on it: the case the bound is for.
sim::PlantConfig held_device() {
  sim::PlantConfig p;
  p.knob = {};
  p.knob.inertia.M = model::kHapticDeviceInertia;
  p.initial_angle = kDisplacement;
  return p;
}

struct Response {
  double start = 0.0;  // rad, largest |θ| over the first 5 ms
  double end = 0.0;    // rad, largest |θ| over the last 20 ms
};

// Released at kDisplacement into τ = K·θ + B·θ̇ (a torque tile and a
// torque_of_velocity tile, built directly: no refusal), 0.2 s simulated.
Response release(double K, double B) {
  testing::CoreHarness h(held_device());
  sim::HandParams hand;
  hand.amplitude_rad = 0.0;  // the hand holds still at θ = 0
  hand.stiffness = model::kGripStiffness;
  hand.damping = model::kGripDamping;
  h.daq().plant().add_effect(sim::make_hand(hand));
  h.set_render(0.0, 0.0);
  auto set = std::make_unique<TileSet>();
  model::PositionTile t;
  t.theta_min = -0.1;  // wide: a growing ring meets the torque limit's clip, not the span's end
  t.theta_max = 0.1;
  const std::vector<double> x = {-0.1, 0.1}, tau = {-0.1 * K, 0.1 * K}, v = {-1.0, 1.0}, tv = {-B, B};
  t.torque_of_angle = model::CubicSpline(x, tau);
  if (B != 0.0) t.torque_of_velocity = model::CubicSpline(v, tv);
  set->position.push_back(t);
  if (!h.core().load_tiles(std::move(set))) throw std::runtime_error("tiles not taken");
  h.run(1);
  h.command(CoreCommand::SetMode, Mode::Render);
  Response r;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const double theta = std::abs(h.step().sample.theta);
    if (i < 50) r.start = std::max(r.start, theta);
    if (i >= n - 200) r.end = std::max(r.end, theta);
  }
  return r;
}

bool settles(double K, double B) { return release(K, B).end < 0.2 * kDisplacement; }

// The largest B ≥ 0 the simulated knob settles with at K = 0, to 2 %.
double simulated_max_damping() {
  double good = 0.0, bad = 0.005;
  while (settles(0.0, bad)) good = bad, bad *= 2.0;
  while (bad - good > 0.02 * bad) {
    const double mid = 0.5 * (good + bad);
    (settles(0.0, mid) ? good : bad) = mid;
  }
  return good;
}

// The largest K the simulated knob settles with, to 1 %.
double simulated_max_stiffness(double B, double guess) {
  double good = 0.0, bad = guess;
  while (settles(bad, B)) good = bad, bad *= 2.0;
  if (good == 0.0) {
    good = guess;
    while (!settles(good, B)) bad = good, good /= 2.0;
  }
  while (bad - good > 0.01 * bad) {
    const double mid = 0.5 * (good + bad);
    (settles(mid, B) ? good : bad) = mid;
  }
  return good;
}

TEST(RenderStabilitySim, TheBoundPredictsTheSimulatedKnobsLargestStableStiffness) {
  const model::LoopStability loop(RenderController::loop_dynamics(testing::CoreHarness::kRate));
  for (const double B : {0.0, 0.002, 0.005}) {
    const double predicted = loop.max_stiffness(B);
    const double measured = simulated_max_stiffness(B, predicted);
    std::printf("B = %.4g N·m·s/rad: K_max predicted %.4g N·m/rad, simulated %.4g N·m/rad (%+.1f %%)\n", B,
                predicted, measured, 100.0 * (predicted / measured - 1.0));
    EXPECT_NEAR(predicted, measured, 0.2 * measured) << "B = " << B;
  }
}

TEST(RenderStabilitySim, TheBoundPredictsTheSimulatedKnobsLargestStableDamping) {
  const model::LoopStability loop(RenderController::loop_dynamics(testing::CoreHarness::kRate));
  const double predicted = loop.max_damping(0.0);
  const double measured = simulated_max_damping();
  std::printf("K = 0: B_max predicted %.4g N·m·s/rad, simulated %.4g N·m·s/rad (%+.1f %%)\n", predicted, measured,
              100.0 * (predicted / measured - 1.0));
  EXPECT_NEAR(predicted, measured, 0.2 * measured);
}

TEST(RenderStabilitySim, ASpringInsideTheBoundSettlesOnTheHandAndOneBeyondItRingsOn) {
  const model::LoopStability loop(RenderController::loop_dynamics(testing::CoreHarness::kRate));
  const double k_max = loop.max_stiffness(0.0);
  const Response inside = release(0.8 * k_max, 0.0);
  const Response beyond = release(1.2 * k_max, 0.0);
  std::printf("K = %.4g N·m/rad (0.8 × bound): |θ| %.3g mrad → %.3g mrad; K = %.4g (1.2 ×): %.3g → %.3g mrad\n",
              0.8 * k_max, inside.start * 1e3, inside.end * 1e3, 1.2 * k_max, beyond.start * 1e3, beyond.end * 1e3);
  EXPECT_LT(inside.end, 0.2 * inside.start) << "the ring decays to a few encoder counts";
  EXPECT_GT(beyond.end, inside.start) << "the ring grows until the torque limit clips it, and goes on";
}

}  // namespace
}  // namespace knoblab::hapticd
