// The cycle as the daemon runs it: modes, commands, safety, recording.
#include <gtest/gtest.h>

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
  cc.calibration = daq.calibration();
  start.capture = capture::CaptureController(cc);
  start.capture_cycles = 60000;  // 6 s at 10 kHz
  ASSERT_TRUE(core.post(start));

  std::int64_t recorded = 0;
  double last_t = -1;
  for (int i = 0; i < 61000; ++i) {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    LoopRecord rec;
    daq.read(in);
    core.cycle(in, {}, 0, 0, out, rec);
    daq.write(out);
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
    core.cycle(in, lines, 0, 0, out, rec);
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

TEST(Core, ExternalFaultsAndForcedSafeLatchUntilCleared) {
  capture::SimDaq daq(plant("moderate-detents"), 10000.0);
  HapticCore core(config(daq));
  CoreCommand c;
  c.kind = CoreCommand::SetMode;
  c.mode = Mode::Render;
  core.post(c);
  std::uint32_t external = 0;
  auto step = [&] {
    capture::DaqInputs in;
    capture::DaqOutputs out;
    LoopRecord rec;
    core.cycle(in, {}, 0, external, out, rec);
    return out;
  };
  EXPECT_TRUE(step().amp_enable);
  external = kFaultAmplifier;
  EXPECT_FALSE(step().amp_enable);
  c.kind = CoreCommand::ClearFault;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);  // the amplifier still reports it
  external = 0;
  EXPECT_FALSE(step().amp_enable);  // gone, but latched until cleared
  c.kind = CoreCommand::ClearFault;
  core.post(c);
  EXPECT_TRUE(step().amp_enable);
  c.kind = CoreCommand::ForceSafe;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);
  EXPECT_EQ(core.state().faults, kFaultCommanded);
  EXPECT_EQ(core.state().mode, Mode::Render);
  c.kind = CoreCommand::ClearFault;
  core.post(c);
  c.kind = CoreCommand::ForceSafe;
  c.faults = kFaultWatchdog;
  core.post(c);
  EXPECT_FALSE(step().amp_enable);
  EXPECT_EQ(core.state().faults, kFaultWatchdog);
}

}  // namespace
}  // namespace knoblab::hapticd
