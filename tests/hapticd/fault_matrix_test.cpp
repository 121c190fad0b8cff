// Each fault in each mode: the cycle in which it latches writes zero command
// with the amplifier disabled, and that cycle's record ends the recording
// with the fault named. Idle and render modes carry a trial recording so that
// there is a recording to say why.
#include <gtest/gtest.h>

#include <string>

#include "core_harness.hpp"

namespace knoblab::hapticd {
namespace {

using testing::CoreHarness;

struct FaultCase {
  const char* name;
  std::uint32_t bit;
  void (*inject)(CoreHarness&);
};

const FaultCase kFaults[] = {
    {"e-stop", kFaultEstop, [](CoreHarness& h) { h.ctx.lines.estop = true; }},
    {"amplifier fault", kFaultAmplifier, [](CoreHarness& h) { h.ctx.external_faults = kFaultAmplifier; }},
    {"lost amplifier link", kFaultAmpComms, [](CoreHarness& h) { h.ctx.external_faults = kFaultAmpComms; }},
    {"DAQ read errors", kFaultIo, [](CoreHarness& h) { h.daq().set_read_failure(true); }},
    {"DAQ write errors", kFaultIo, [](CoreHarness& h) { h.daq().set_write_failure(true); }},
    {"NaN on the torque channel", kFaultNonFinite, [](CoreHarness& h) { h.torque_channel_nan = true; }},
    {"client watchdog", kFaultWatchdog,
     [](CoreHarness& h) {
       CoreCommand c;
       c.kind = CoreCommand::ForceSafe;
       c.faults = kFaultWatchdog;
       h.post(c);
     }},
    {"loop overruns", kFaultOverruns, [](CoreHarness& h) { h.ctx.consecutive_overruns = 11; }},
};

struct ModeCase {
  const char* name;
  Mode mode;
  bool drives;  // the amplifier is enabled before the fault
  void (*enter)(CoreHarness&);
};

const ModeCase kModes[] = {
    {"idle (trial)", Mode::Idle, false, [](CoreHarness& h) { h.command(CoreCommand::StartRecording); }},
    {"render (trial)", Mode::Render, true,
     [](CoreHarness& h) {
       h.set_render(0.002, 0.02);
       h.command(CoreCommand::SetMode, Mode::Render);
       h.command(CoreCommand::StartRecording);
     }},
    {"capture", Mode::Capture, true, [](CoreHarness& h) { h.start_capture(100000); }},
    {"calibrate", Mode::Calibrate, true, [](CoreHarness& h) { h.start_calibration(5.0); }},
};

TEST(FaultMatrix, EveryFaultInEveryModeIsSafeInTheCycleItLatchesAndTheRecordingSaysWhy) {
  for (const ModeCase& m : kModes) {
    for (const FaultCase& f : kFaults) {
      SCOPED_TRACE(std::string(f.name) + " in " + m.name);
      CoreHarness h;
      m.enter(h);
      h.run(50);
      ASSERT_EQ(h.core().state().mode, m.mode);
      ASSERT_NE(h.core().state().recording_id, 0u);
      ASSERT_EQ(h.last_out.amp_enable, m.drives);
      const std::uint32_t recording = h.core().state().recording_id;

      f.inject(h);
      LoopRecord latched{};
      int cycles = 0;
      for (; cycles < 10; ++cycles) {
        latched = h.step();
        if (latched.faults != 0) break;
        // Until it latches (I/O: the first two failed cycles) the mode goes on.
        ASSERT_EQ(latched.end, RecordingEnd::none);
      }
      ASSERT_NE(latched.faults, 0u) << "never latched";
      EXPECT_EQ(latched.faults, f.bit) << fault_list(latched.faults);
      EXPECT_EQ(h.last_out.motor_command_V, 0.0);
      EXPECT_FALSE(h.last_out.amp_enable);
      EXPECT_EQ(latched.sample.command, 0.0);
      EXPECT_TRUE(latched.sample.flags & interchange::kFaultLatched);
      EXPECT_FALSE(latched.sample.flags & interchange::kAmpEnabled);
      EXPECT_EQ(latched.recording_id, recording);
      EXPECT_EQ(latched.end, RecordingEnd::fault);
      // I/O latches on the third failed cycle in a row; a failed write is
      // known one cycle later than a failed read.
      const int expected = std::string(f.name) == "DAQ read errors" ? 2 : std::string(f.name) == "DAQ write errors" ? 3 : 0;
      EXPECT_EQ(cycles, expected);

      h.step();
      EXPECT_EQ(h.core().state().mode, Mode::Idle);
      EXPECT_EQ(h.core().state().recording_id, 0u);
      EXPECT_FALSE(h.last_out.amp_enable);
    }
  }
}

// Tracking belongs to capture mode alone: a knob at its end stop, the sweep
// pushing it on. The cycle that finds it lost is safe and ends the capture.
TEST(FaultMatrix, ACaptureThatLosesTheKnobLatchesTrackingAndEndsOnThatCycle) {
  sim::PlantConfig plant = testing::plant_with("moderate-detents");
  plant.knob.walls.lo = -0.3;  // rad: stops well inside the sweep's ±1 rad
  plant.knob.walls.hi = 0.3;
  plant.knob.walls.K = 10.0;  // N·m/rad: 18 mrad under the full torque limit
  CoreHarness h(plant);
  h.start_capture(static_cast<std::int64_t>(3 * CoreHarness::kRate));
  LoopRecord latched{};
  for (int i = 0; i < 3 * static_cast<int>(CoreHarness::kRate); ++i) {
    latched = h.step();
    if (latched.faults != 0) break;
  }
  ASSERT_EQ(latched.faults, kFaultTracking) << fault_list(latched.faults);
  EXPECT_EQ(latched.end, RecordingEnd::fault);
  EXPECT_EQ(latched.mode, Mode::Capture);
  EXPECT_FALSE(h.last_out.amp_enable);
  EXPECT_EQ(h.last_out.motor_command_V, 0.0);
  // Off by more than 0.1 rad for the 20 ms before: the sweep past 0.4 rad.
  const double ref = model::SweptSine::spatial().theta(latched.sample.t - 0.02);
  EXPECT_GT(ref, 0.4);
  EXPECT_LT(latched.sample.theta, 0.35);
  h.step();
  EXPECT_EQ(h.core().state().mode, Mode::Idle);
  // Not capturing, the cause is gone: a clear releases it.
  h.command(CoreCommand::ClearFault);
  h.run(2);
  EXPECT_EQ(h.core().state().faults, 0u);
}

TEST(FaultMatrix, OneOrTwoFailedIoCyclesInARowAreToleratedAndTheCountRestarts) {
  CoreHarness h;
  h.set_render(0.002, 0.02);
  h.command(CoreCommand::SetMode, Mode::Render);
  h.run(10);
  for (int burst = 0; burst < 20; ++burst) {
    h.daq().set_read_failure(true);
    h.run(2);
    h.daq().set_read_failure(false);
    h.run(1);
  }
  EXPECT_EQ(h.core().state().faults, 0u);
  EXPECT_TRUE(h.last_out.amp_enable);
}

}  // namespace
}  // namespace knoblab::hapticd
