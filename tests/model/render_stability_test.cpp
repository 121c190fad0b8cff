// The render loop's stability region (Z-width): the eigenvalue routine on
// known roots, the classical bound it must reproduce, and the shape of the
// region on the default grip (negative damping and stiffness included).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <vector>

#include "knoblab/model/render_stability.hpp"

namespace knoblab::model {
namespace {

TEST(Eigenvalues, FindTheRootsOfACompanionMatrix) {
  // (z − 0.5)(z + 0.9)(z² − 1.2z + 0.72): roots 0.5, −0.9, 0.6 ± 0.6i.
  // The polynomial is built from its factors, the matrix is its companion.
  std::vector<std::complex<double>> roots = {0.5, -0.9, {0.6, 0.6}, {0.6, -0.6}};
  std::vector<std::complex<double>> p = {1.0};
  for (const auto r : roots) {
    std::vector<std::complex<double>> q(p.size() + 1, 0.0);
    for (std::size_t i = 0; i < p.size(); ++i) {
      q[i] += p[i];
      q[i + 1] -= r * p[i];
    }
    p = q;
  }
  const int n = 4;
  std::vector<double> a(n * n, 0.0);
  for (int j = 0; j < n; ++j) a[j] = -p[j + 1].real();
  for (int i = 1; i < n; ++i) a[i * n + i - 1] = 1.0;
  auto eig = eigenvalues(a, n);
  ASSERT_EQ(eig.size(), 4u);
  for (const auto r : roots) {
    double nearest = 1e9;
    for (const auto e : eig) nearest = std::min(nearest, std::abs(e - r));
    EXPECT_LT(nearest, 1e-10) << r;
  }
}

// Colgate & Schenkel's virtual wall: a heavy mass with physical damping b
// and a spring through a zero-order hold, no velocity feedback, renders
// stably up to K ≈ 2b/T.
TEST(RenderStability, AHeavyDampedMassMeetsTheClassicalVirtualWallBound) {
  LoopDynamics d;  // one rigid body, an ideal actuator
  d.rotor_inertia = 0.0;
  d.actuator_bandwidth_hz = 0.0;
  d.inertia = 1.0;
  d.damping = 0.01;
  d.grip_stiffness = 0.0;
  const double bound = 2.0 * d.damping * d.rate_hz;  // 200 N·m/rad
  EXPECT_NEAR(max_stiffness(d, 0.0), bound, 0.03 * bound);
  EXPECT_TRUE(renders_stably(d, 0.9 * bound, 0.0));
  EXPECT_FALSE(renders_stably(d, 1.1 * bound, 0.0));
}

TEST(RenderStability, RenderedDampingRingsThroughTheVelocityFiltersLagLongBeforeTheTorqueLimit) {
  const LoopStability loop{LoopDynamics{}};
  const double b_max = loop.max_damping(0.0);
  ASSERT_TRUE(std::isfinite(b_max));
  // The 10th-order 500 Hz filter delays ω̂ by about a millisecond: a
  // damping past the grip's own rings at the grip's frequency.
  EXPECT_GT(b_max, 0.5 * kGripDamping);
  EXPECT_LT(b_max, 3.0 * kGripDamping);
  EXPECT_FALSE(loop.renders_stably(0.0, 1.2 * b_max));
  EXPECT_TRUE(loop.renders_stably(0.0, 0.8 * b_max));
  // Nor does it buy stiffness: near the Nyquist rate, where the zero-order
  // hold's ring lives, the filter passes no velocity at all.
  const double k0 = loop.max_stiffness(0.0);
  EXPECT_NEAR(loop.max_stiffness(0.2 * b_max), k0, 0.05 * k0);
  EXPECT_GT(loop.max_damping(0.5 * k0), b_max) << "a stiffer spring lifts the grip's mode away from the lag";
}

TEST(RenderStability, AStribeckDownSlopeRendersOnlyWhileTheGripOutweighsIt) {
  const LoopDynamics d;
  const double b_min = min_damping(d, 0.0);
  EXPECT_LT(b_min, 0.0);
  EXPECT_NEAR(b_min, -d.damping, 0.2 * d.damping) << "about the grip's own damping";
  EXPECT_TRUE(renders_stably(d, 0.0, 0.5 * b_min));
  EXPECT_FALSE(renders_stably(d, 0.0, 1.5 * b_min)) << "the knob would ring on the hand";
}

TEST(RenderStability, TheFallingSideOfADetentRendersStably) {
  const LoopStability loop{LoopDynamics{}};
  // A 12-per-revolution detent of 10 mN·m falls at up to 0.75 N·m/rad; a
  // steep one beyond the grip's 1 N·m/rad pushes the knob away, as drawn.
  EXPECT_TRUE(loop.renders_stably(-0.75, 0.0));
  EXPECT_TRUE(loop.renders_stably(-5.0, 0.0));
  EXPECT_TRUE(loop.renders_stably(-5.0, 0.002));
  EXPECT_GT(loop.spectral_radius(-0.5, 0.0), 0.99) << "a slow mode: the knob on its grip";
}

TEST(RenderStability, HowSteepAFallRendersIsTheLeastStableStiffness) {
  const LoopStability loop{LoopDynamics{}};
  const double k_min = loop.min_stiffness(0.0);
  std::printf("the steepest fall that renders: %.4g N·m/rad (B = 0)\n", k_min);
  ASSERT_TRUE(std::isfinite(k_min));
  EXPECT_LT(k_min, -5.0) << "the falls above render";
  EXPECT_TRUE(loop.renders_stably(k_min, 0.0));
  EXPECT_FALSE(loop.renders_stably(1.001 * k_min, 0.0));
  EXPECT_TRUE(std::isnan(loop.min_stiffness(1.2 * loop.max_damping(0.0)))) << "no fall renders where no spring does";
  LoopDynamics slow;  // a 1 kHz loop, as the UI tests run hapticd: no fall is steep enough to ring
  slow.rate_hz = 1000.0;
  slow.velocity_cutoff_hz = 200.0;
  EXPECT_EQ(LoopStability(slow).min_stiffness(0.0), -std::numeric_limits<double>::infinity());
}

TEST(RenderStability, TheFreeFunctionsAndTheClassAgree) {
  const LoopDynamics d;
  const LoopStability loop(d);
  EXPECT_EQ(max_stiffness(d, 0.001), loop.max_stiffness(0.001));
  EXPECT_EQ(max_damping(d, 20.0), loop.max_damping(20.0));
  EXPECT_EQ(renders_stably(d, 30.0, 0.001), loop.renders_stably(30.0, 0.001));
  LoopDynamics no_rate;
  no_rate.rate_hz = 0.0;
  EXPECT_THROW(LoopStability{no_rate}, std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::model
