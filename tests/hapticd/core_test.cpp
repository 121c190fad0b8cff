// The cycle as the daemon runs it: modes, commands, safety, recording.
#include <gtest/gtest.h>

#include <cmath>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hapticd/core.hpp"
#include "knoblab/sim/presets.hpp"

namespace knoblab::hapticd {
namespace {

CoreConfig config(const capture::SimDaq& daq) {
  CoreConfig c;
  c.rate_hz = 10000.0;
  c.calibration = daq.calibration();
  return c;
}

sim::PlantConfig plant(const char* knob) {
  sim::PlantConfig p;
  p.knob = *sim::presets::knob(knob);
  return p;
}

TEST(Core, CaptureRecordsExactlyItsCyclesThenGoesIdle) {
  capture::SimDaq daq(plant("moderate-detents"), 10000.0);
  HapticCore core(config(daq));
  CoreCommand start;
  start.kind = CoreCommand::StartCapture;
  capture::CaptureConfig cc;
  cc.rate_hz = 10000.0;
  start.capture = capture::CaptureController(cc);
  start.capture_cycles = 60000;  // 6 s at 10 kHz
  ASSERT_TRUE(core.post(start));

  std::int64_t recorded = 0;
  double last_t = -1;
  for (int i = 0; i < 61000; ++i) {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    LoopRecord rec;
    EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
    core.cycle(in, {}, out, rec);
    EXPECT_EQ(daq.write(out), capture::IoStatus::ok);
    if (rec.recording_id == 1) {
      ASSERT_EQ(rec.sample.t, static_cast<double>(recorded) * (1.0 / 10000.0));
      ++recorded;
      last_t = rec.sample.t;
      EXPECT_EQ(rec.mode, Mode::Capture);
    } else {
      EXPECT_EQ(rec.recording_id, 0u);
      EXPECT_FALSE(out.amp_enable);  // idle: amplifier off
    }
  }
  EXPECT_EQ(recorded, 60000);
  EXPECT_DOUBLE_EQ(last_t, 59999.0 / 10000.0);
  EXPECT_EQ(core.state().mode, Mode::Idle);
}

TEST(Core, EstopMidRenderIsSafeInTheSameCycle) {
  capture::SimDaq daq(plant("high-friction"), 10000.0);
  HapticCore core(config(daq));
  CoreCommand c;
  c.kind = CoreCommand::SetRender;
  c.immediate = true;
  c.render.B_vel = 0.02;
  c.render.A_pos = 0.03;
  c.render.P_pos = 1.0 / 12.0;
  ASSERT_TRUE(core.post(c));
  c.kind = CoreCommand::SetMode;
  c.mode = Mode::Render;
  ASSERT_TRUE(core.post(c));

  int driving = 0;
  for (int i = 0; i < 2000; ++i) {
    capture::DaqInputs in;
    in.encoder_counts = 200 * i;  // a hand turning the knob at ≈ 20 rad/s
    capture::DaqOutputs out;
    LoopRecord rec;
    LineInputs lines;
    lines.estop = i >= 1000;
    CycleContext ctx;
    ctx.lines = lines;
    core.cycle(in, ctx, out, rec);
    if (i < 1000) {
      driving += out.amp_enable && out.motor_command_V != 0.0;
    } else {
      ASSERT_EQ(out.motor_command_V, 0.0) << i;
      ASSERT_FALSE(out.amp_enable) << i;
      ASSERT_EQ(rec.sample.command, 0.0);
      ASSERT_TRUE(rec.sample.flags & interchange::kEstopActive);
      ASSERT_TRUE(rec.sample.flags & interchange::kFaultLatched);
      ASSERT_FALSE(rec.sample.flags & interchange::kAmpEnabled);
    }
  }
  EXPECT_GT(driving, 900);
  EXPECT_EQ(core.state().faults, kFaultEstop);
}

TEST(Core, ExternalFaultsAndForcedSafeLatchUntilClearedAndNothingResumesByItself) {
  capture::SimDaq daq(plant("moderate-detents"), 10000.0);
  HapticCore core(config(daq));
  CoreCommand c;
  c.kind = CoreCommand::SetMode;
  c.mode = Mode::Render;
  core.post(c);
  CycleContext ctx;
  auto step = [&] {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    LoopRecord rec;
    core.cycle(in, ctx, out, rec);
    return out;
  };
  EXPECT_TRUE(step().amp_enable);
  ctx.external_faults = kFaultAmplifier;
  EXPECT_FALSE(step().amp_enable);
  EXPECT_EQ(core.state().mode, Mode::Idle);  // a fault ends rendering
  c.kind = CoreCommand::ClearFault;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);  // the amplifier still reports it
  EXPECT_EQ(core.state().faults, kFaultAmplifier);
  ctx.external_faults = 0;
  EXPECT_FALSE(step().amp_enable);  // gone, but latched until cleared
  c.kind = CoreCommand::SetMode;
  c.mode = Mode::Render;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);  // refused while faulted
  EXPECT_EQ(core.state().mode, Mode::Idle);
  c.kind = CoreCommand::ClearFault;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);  // cleared, and idle: the client asks again
  EXPECT_EQ(core.state().faults, 0u);
  c.kind = CoreCommand::SetMode;
  core.post(c);
  EXPECT_TRUE(step().amp_enable);
  c.kind = CoreCommand::ForceSafe;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);
  EXPECT_EQ(core.state().faults, kFaultCommanded);
  c.kind = CoreCommand::ClearFault;
  core.post(c);
  c.kind = CoreCommand::ForceSafe;
  c.faults = kFaultWatchdog;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);
  EXPECT_EQ(core.state().faults, kFaultWatchdog);
}

// The watchdog's and the store's safe-state requests once went through the
// command queue and were dropped when it was full. They cannot be now: the
// queue full (a ClearFault queued in it, too), the motor is safe in the
// very next cycle and stays so.
TEST(Core, ASafeStateRequestIsTakenInTheNextCycleHoweverFullTheCommandQueue) {
  capture::SimDaq daq(plant("moderate-detents"), 10000.0);
  HapticCore core(config(daq));
  CoreCommand c;
  c.kind = CoreCommand::SetMode;
  c.mode = Mode::Render;
  ASSERT_TRUE(core.post(c));
  auto step = [&] {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    LoopRecord rec;
    EXPECT_EQ(daq.read(in), capture::IoStatus::ok);
    core.cycle(in, {}, out, rec);
    EXPECT_EQ(daq.write(out), capture::IoStatus::ok);
    return out;
  };
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(step().amp_enable);
  c.kind = CoreCommand::ClearFault;
  ASSERT_TRUE(core.post(c));
  c.kind = CoreCommand::SetRender;
  int queued = 1;
  while (core.post(c)) ++queued;
  EXPECT_GE(queued, 8);
  EXPECT_FALSE(core.post(c)) << "the queue is full";
  core.request_safe(kFaultWatchdog);
  const capture::DaqOutputs out = step();
  EXPECT_FALSE(out.amp_enable);
  EXPECT_EQ(out.motor_command_V, 0.0);
  EXPECT_EQ(core.state().faults, kFaultWatchdog);
  EXPECT_EQ(core.state().mode, Mode::Idle);
  for (int i = 0; i < 20; ++i) EXPECT_FALSE(step().amp_enable);  // the queue drains; still latched
  EXPECT_EQ(core.state().faults, kFaultWatchdog);
}

// A hand turning the knob at a steady 2 rad/s: encoder counts only.
capture::DaqInputs turned_by_hand(const capture::SensorCalibration& cal, int cycle) {
  capture::DaqInputs in;
  const double theta = 2.0 * cycle / 10000.0;
  in.encoder_counts = static_cast<std::int64_t>(std::llround(theta / (2.0 * M_PI) * cal.counts_per_rev));
  in.torque_V = cal.torque_offset_V;
  return in;
}

TEST(Core, IdleRecordsTheVelocityOfAKnobTurnedByHand) {
  capture::SimDaq daq(plant("moderate-detents"), 10000.0);
  HapticCore core(config(daq));
  CoreCommand c;
  c.kind = CoreCommand::StartRecording;  // a trial in idle mode
  ASSERT_TRUE(core.post(c));
  LoopRecord rec;
  capture::DaqOutputs out;
  for (int i = 0; i < 3000; ++i) core.cycle(turned_by_hand(daq.calibration(), i), {}, out, rec);
  EXPECT_EQ(rec.mode, Mode::Idle);
  EXPECT_NE(rec.recording_id, 0u);
  EXPECT_NEAR(rec.sample.omega, 2.0, 0.05);
}

TEST(Core, EnteringRenderDoesNotRestartTheVelocityEstimate) {
  capture::SimDaq daq(plant("moderate-detents"), 10000.0);
  HapticCore core(config(daq));
  LoopRecord rec;
  capture::DaqOutputs out;
  int i = 0;
  for (; i < 3000; ++i) core.cycle(turned_by_hand(daq.calibration(), i), {}, out, rec);
  CoreCommand c;
  c.kind = CoreCommand::SetMode;
  c.mode = Mode::Render;
  ASSERT_TRUE(core.post(c));
  core.cycle(turned_by_hand(daq.calibration(), i), {}, out, rec);
  ASSERT_EQ(rec.mode, Mode::Render);
  // One sensor front end ran all along: the first render cycle already knows
  // the knob's speed (a restarted filter would start from 0).
  EXPECT_NEAR(rec.sample.omega, 2.0, 0.05);
}

// The button's count passes through to state(); the core starts nothing on a
// press (the front-end decides what one means).
TEST(Core, PublishesCaptureButtonPressesAndActsOnNone) {
  capture::SimDaq daq(plant("moderate-detents"), 10000.0);
  HapticCore core(config(daq));
  CycleContext ctx;
  LoopRecord rec;
  capture::DaqOutputs out;
  for (int i = 0; i < 100; ++i) {
    capture::DaqInputs in;
    (void)daq.read(in);
    ctx.lines.capture_presses = static_cast<std::uint64_t>(i / 10);  // a press every 10 cycles
    ctx.lines.capture_button = i % 10 < 5;
    core.cycle(in, ctx, out, rec);
    ASSERT_EQ(core.state().button_presses, static_cast<std::uint64_t>(i / 10)) << i;
    ASSERT_EQ(rec.mode, Mode::Idle) << i;
    ASSERT_EQ(rec.recording_id, 0u) << i;
    ASSERT_FALSE(out.amp_enable) << i;
  }
}

}  // namespace
}  // namespace knoblab::hapticd
