#include <gtest/gtest.h>

#include <cmath>

#include "knoblab/hapticd/virtual_mass.hpp"

namespace knoblab::hapticd {
namespace {

TEST(VirtualMass, ConstantAccelerationFeelsLikeMTimesAlpha) {
  VirtualMass vm;
  const double M = 2e-4, K = 12.0, B = 0.088, dt = 1e-4, alpha = 50.0;
  double tau = 0;
  for (int i = 0; i <= 5000; ++i) {  // 0.5 s: the coupling has settled
    const double t = i * dt;
    tau = vm.update(M, K, B, 0.5 * alpha * t * t, alpha * t, dt);
  }
  EXPECT_NEAR(tau, M * alpha, 0.02 * M * alpha);
}

TEST(VirtualMass, ConstantSpeedFeelsNothingOnceSettled) {
  VirtualMass vm;
  double tau = 1;
  for (int i = 0; i <= 5000; ++i) tau = vm.update(3e-4, 12.0, 0.088, 2.0 * i * 1e-4, 2.0, 1e-4);
  EXPECT_NEAR(tau, 0.0, 1e-6);
}

TEST(VirtualMass, StaysStableForATinyMassAndStiffCoupling) {
  VirtualMass vm;
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const double theta = std::sin(i * 1e-3);  // a wiggling hand
    worst = std::max(worst, std::abs(vm.update(1e-9, 1000.0, 1.0, theta, std::cos(i * 1e-3) * 10.0, 1e-4)));
  }
  EXPECT_LT(worst, 1.0);  // explicit Euler would blow up here
}

TEST(VirtualMass, NoMassNoTorque) {
  VirtualMass vm;
  EXPECT_EQ(vm.update(0.0, 12.0, 0.088, 1.0, 5.0, 1e-4), 0.0);
}

}  // namespace
}  // namespace knoblab::hapticd
