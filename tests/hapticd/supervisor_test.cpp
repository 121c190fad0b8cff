#include <gtest/gtest.h>

#include <limits>

#include "knoblab/hapticd/supervisor.hpp"

namespace knoblab::hapticd {
namespace {

capture::DaqOutputs driving(double volts) { return {volts, true}; }

TEST(Supervisor, EstopZeroesAndDisablesInTheSameCycleAndLatches) {
  Supervisor sup;
  auto out = driving(3.0);
  sup.apply({}, out);
  EXPECT_EQ(out.motor_command_V, 3.0);
  EXPECT_TRUE(out.amp_enable);

  SafetyInputs in;
  in.estop = true;
  out = driving(3.0);
  sup.apply(in, out);
  EXPECT_EQ(out.motor_command_V, 0.0);
  EXPECT_FALSE(out.amp_enable);
  EXPECT_EQ(sup.latched(), kFaultEstop);

  // Released but not cleared: still safe.
  out = driving(3.0);
  sup.apply({}, out);
  EXPECT_FALSE(out.amp_enable);
  // A clear while the cause persists does not release.
  in.clear_requested = true;
  out = driving(3.0);
  sup.apply(in, out);
  EXPECT_FALSE(out.amp_enable);
  // Released and cleared: drives again.
  SafetyInputs clear;
  clear.clear_requested = true;
  out = driving(3.0);
  sup.apply(clear, out);
  EXPECT_TRUE(out.amp_enable);
  EXPECT_EQ(out.motor_command_V, 3.0);
}

TEST(Supervisor, ClipsTheCommandToTheTorqueLimit) {
  SafetyLimits limits;
  limits.torque_limit_Nm = 0.1;
  Supervisor sup(limits);
  const double limit_V = 0.1 / limits.torque_per_volt;
  auto out = driving(100.0);
  EXPECT_TRUE(sup.apply({}, out));
  EXPECT_DOUBLE_EQ(out.motor_command_V, limit_V);
  out = driving(-100.0);
  EXPECT_TRUE(sup.apply({}, out));
  EXPECT_DOUBLE_EQ(out.motor_command_V, -limit_V);
  out = driving(0.5 * limit_V);
  EXPECT_FALSE(sup.apply({}, out));
  EXPECT_TRUE(out.amp_enable);
}

TEST(Supervisor, VelocityOverrunsAndExternalFaultsEachGoSafe) {
  struct Case {
    SafetyInputs in;
    std::uint32_t fault;
  };
  SafetyInputs fast, late, amp, dog;
  fast.omega = -60.0;
  late.consecutive_overruns = 11;
  amp.external_faults = kFaultAmplifier;
  dog.external_faults = kFaultWatchdog;
  for (const Case& c : {Case{fast, kFaultVelocity}, Case{late, kFaultOverruns}, Case{amp, kFaultAmplifier},
                        Case{dog, kFaultWatchdog}}) {
    Supervisor sup;
    auto out = driving(1.0);
    sup.apply(c.in, out);
    EXPECT_EQ(sup.latched(), c.fault);
    EXPECT_FALSE(out.amp_enable);
    EXPECT_EQ(out.motor_command_V, 0.0);
  }
  Supervisor sup;
  SafetyInputs ok;
  ok.consecutive_overruns = 10;  // at the limit is still fine
  ok.omega = 49.0;
  auto out = driving(1.0);
  sup.apply(ok, out);
  EXPECT_EQ(sup.latched(), 0u);
}

TEST(Supervisor, NonFiniteVelocityCommandOrReadingsGoSafeWhereTheLimitsAloneWouldLetThemThrough) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    double omega, command;
    bool sensors_finite;
  };
  for (const Case& c : {Case{nan, 1.0, true}, Case{-inf, 1.0, true}, Case{0.0, nan, true},
                        Case{0.0, inf, true}, Case{0.0, 1.0, false}}) {
    Supervisor sup;
    SafetyInputs in;
    in.omega = c.omega;
    in.sensors_finite = c.sensors_finite;
    auto out = driving(c.command);
    sup.apply(in, out);
    EXPECT_TRUE(sup.latched() & kFaultNonFinite) << c.omega << " " << c.command;  // -inf is fast, too
    EXPECT_EQ(out.motor_command_V, 0.0);
    EXPECT_FALSE(out.amp_enable);
  }
}

TEST(Supervisor, IoErrorsLatchAtTheConfiguredCountInARow) {
  SafetyLimits limits;
  limits.max_consecutive_io_errors = 3;
  Supervisor sup(limits);
  SafetyInputs in;
  in.consecutive_io_errors = 2;
  auto out = driving(1.0);
  sup.apply(in, out);
  EXPECT_EQ(sup.latched(), 0u);
  EXPECT_TRUE(out.amp_enable);
  in.consecutive_io_errors = 3;
  out = driving(1.0);
  sup.apply(in, out);
  EXPECT_EQ(sup.latched(), kFaultIo);
  EXPECT_FALSE(out.amp_enable);
}

TEST(Supervisor, ALostCaptureLatchesTrackingAndClearsOnceTheCaptureIsGone) {
  Supervisor sup;
  SafetyInputs in;
  in.tracking_lost = true;
  auto out = driving(11.0);
  sup.apply(in, out);
  EXPECT_EQ(sup.latched(), kFaultTracking);
  EXPECT_EQ(out.motor_command_V, 0.0);
  EXPECT_FALSE(out.amp_enable);
  SafetyInputs clear;
  clear.clear_requested = true;
  out = driving(1.0);
  sup.apply(clear, out);
  EXPECT_EQ(sup.latched(), 0u);
  EXPECT_TRUE(out.amp_enable);
}

TEST(Supervisor, FaultListNamesEachLatchedFaultOnceInTableOrder) {
  EXPECT_EQ(fault_list(0), "");
  EXPECT_EQ(fault_list(kFaultVelocity | kFaultEstop), "estop,velocity");
  EXPECT_EQ(fault_list(kFaultIo | kFaultNonFinite | kFaultRecording), "io,non_finite,recording");
  EXPECT_EQ(fault_list(kFaultTracking | kFaultVelocity), "velocity,tracking");
}

}  // namespace
}  // namespace knoblab::hapticd
