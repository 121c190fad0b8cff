// Every row of HapticCore's state machine (core.hpp): from each state, each
// event, the mode after it, whether a recording is open, and how the record
// of the event's cycle says the recording ended.
#include <gtest/gtest.h>

#include <string>

#include "core_harness.hpp"

namespace knoblab::hapticd {
namespace {

using testing::CoreHarness;

enum class From { Idle, Render, IdleTrial, RenderTrial, Capture, Calibrate };
enum class Event {
  SetIdle, SetRender, StartCapture, StopCapture, StartCalibration, StartTrial, StopTrial,
  RunFinishes, Fault
};

const char* name(From f) {
  switch (f) {
    case From::Idle: return "idle";
    case From::Render: return "render";
    case From::IdleTrial: return "idle+trial";
    case From::RenderTrial: return "render+trial";
    case From::Capture: return "capture";
    case From::Calibrate: return "calibrate";
  }
  return "?";
}

const char* name(Event e) {
  switch (e) {
    case Event::SetIdle: return "set_mode idle";
    case Event::SetRender: return "set_mode render";
    case Event::StartCapture: return "start_capture";
    case Event::StopCapture: return "stop_capture";
    case Event::StartCalibration: return "calibrate";
    case Event::StartTrial: return "start_trial";
    case Event::StopTrial: return "stop_trial";
    case Event::RunFinishes: return "the run's last cycle";
    case Event::Fault: return "a fault";
  }
  return "?";
}

struct Row {
  From from;
  Event event;
  Mode mode_after;
  bool recording_after;
  RecordingEnd end;  // on the event cycle's record
};

// A run set up for a row lasts this long unless the row finishes it.
constexpr int kSetupCycles = 20;
constexpr std::int64_t kLongRun = 100000;

void enter(CoreHarness& h, From from, Event event) {
  const bool finishes = event == Event::RunFinishes;
  switch (from) {
    case From::Idle: break;
    case From::Render: h.command(CoreCommand::SetMode, Mode::Render); break;
    case From::IdleTrial: h.command(CoreCommand::StartRecording); break;
    case From::RenderTrial:
      h.command(CoreCommand::SetMode, Mode::Render);
      h.command(CoreCommand::StartRecording);
      break;
    case From::Capture: h.start_capture(finishes ? kSetupCycles + 1 : kLongRun); break;
    case From::Calibrate: h.start_calibration(finishes ? (kSetupCycles + 1) / CoreHarness::kRate : 5.0); break;
  }
  h.run(kSetupCycles);
}

void send(CoreHarness& h, Event e) {
  switch (e) {
    case Event::SetIdle: h.command(CoreCommand::SetMode, Mode::Idle); break;
    case Event::SetRender: h.command(CoreCommand::SetMode, Mode::Render); break;
    case Event::StartCapture: h.start_capture(kLongRun); break;
    case Event::StopCapture: h.command(CoreCommand::StopCapture); break;
    case Event::StartCalibration: h.start_calibration(5.0); break;
    case Event::StartTrial: h.command(CoreCommand::StartRecording); break;
    case Event::StopTrial: h.command(CoreCommand::StopRecording); break;
    case Event::RunFinishes: break;  // the run set up by enter() ends in this cycle
    case Event::Fault: h.command(CoreCommand::ForceSafe); break;
  }
}

using E = RecordingEnd;
const Row kRows[] = {
    // from idle
    {From::Idle, Event::SetIdle, Mode::Idle, false, E::none},
    {From::Idle, Event::SetRender, Mode::Render, false, E::none},
    {From::Idle, Event::StartCapture, Mode::Capture, true, E::none},
    {From::Idle, Event::StopCapture, Mode::Idle, false, E::none},
    {From::Idle, Event::StartCalibration, Mode::Calibrate, true, E::none},
    {From::Idle, Event::StartTrial, Mode::Idle, true, E::none},
    {From::Idle, Event::StopTrial, Mode::Idle, false, E::none},
    {From::Idle, Event::Fault, Mode::Idle, false, E::none},
    // from render
    {From::Render, Event::SetIdle, Mode::Idle, false, E::none},
    {From::Render, Event::SetRender, Mode::Render, false, E::none},
    {From::Render, Event::StartCapture, Mode::Capture, true, E::none},
    {From::Render, Event::StopCapture, Mode::Render, false, E::none},
    {From::Render, Event::StartCalibration, Mode::Calibrate, true, E::none},
    {From::Render, Event::StartTrial, Mode::Render, true, E::none},
    {From::Render, Event::StopTrial, Mode::Render, false, E::none},
    {From::Render, Event::Fault, Mode::Idle, false, E::none},
    // a trial recording open: runs wait for it, mode changes keep it
    {From::IdleTrial, Event::SetRender, Mode::Render, true, E::none},
    {From::IdleTrial, Event::StartCapture, Mode::Idle, true, E::none},
    {From::IdleTrial, Event::StartCalibration, Mode::Idle, true, E::none},
    {From::IdleTrial, Event::StopTrial, Mode::Idle, false, E::finished},
    {From::IdleTrial, Event::Fault, Mode::Idle, false, E::fault},
    {From::RenderTrial, Event::SetIdle, Mode::Idle, true, E::none},
    {From::RenderTrial, Event::StopCapture, Mode::Render, true, E::none},
    {From::RenderTrial, Event::StartTrial, Mode::Render, true, E::none},
    {From::RenderTrial, Event::StopTrial, Mode::Render, false, E::finished},
    {From::RenderTrial, Event::Fault, Mode::Idle, false, E::fault},
    // from a capture
    {From::Capture, Event::SetIdle, Mode::Idle, false, E::stopped},
    {From::Capture, Event::SetRender, Mode::Render, false, E::stopped},
    {From::Capture, Event::StartCapture, Mode::Capture, true, E::none},
    {From::Capture, Event::StopCapture, Mode::Idle, false, E::stopped},
    {From::Capture, Event::StartCalibration, Mode::Capture, true, E::none},
    {From::Capture, Event::StartTrial, Mode::Capture, true, E::none},
    {From::Capture, Event::StopTrial, Mode::Capture, true, E::none},
    {From::Capture, Event::RunFinishes, Mode::Idle, false, E::finished},
    {From::Capture, Event::Fault, Mode::Idle, false, E::fault},
    // from a calibration run
    {From::Calibrate, Event::SetIdle, Mode::Idle, false, E::stopped},
    {From::Calibrate, Event::SetRender, Mode::Render, false, E::stopped},
    {From::Calibrate, Event::StartCapture, Mode::Calibrate, true, E::none},
    {From::Calibrate, Event::StopCapture, Mode::Idle, false, E::stopped},
    {From::Calibrate, Event::StartCalibration, Mode::Calibrate, true, E::none},
    {From::Calibrate, Event::StartTrial, Mode::Calibrate, true, E::none},
    {From::Calibrate, Event::StopTrial, Mode::Calibrate, true, E::none},
    {From::Calibrate, Event::RunFinishes, Mode::Idle, false, E::finished},
    {From::Calibrate, Event::Fault, Mode::Idle, false, E::fault},
};

TEST(CoreStateMachine, EveryStateAnswersEveryEventAsTheTableSays) {
  for (const Row& row : kRows) {
    SCOPED_TRACE(std::string(name(row.from)) + " + " + name(row.event));
    CoreHarness h;
    enter(h, row.from, row.event);
    const std::uint32_t recording_before = h.core().state().recording_id;
    send(h, row.event);
    const LoopRecord event_cycle = h.step();
    EXPECT_EQ(to_string(event_cycle.end), std::string(to_string(row.end)));
    if (row.end != E::none) {
      EXPECT_EQ(event_cycle.recording_id, recording_before);  // its last record
    }
    h.step();
    EXPECT_EQ(to_string(h.core().state().mode), std::string(to_string(row.mode_after)));
    EXPECT_EQ(h.core().state().recording_id != 0, row.recording_after);
  }
}

TEST(CoreStateMachine, ARecordingHoldsOnlyItsOwnModesSamplesAndEndsExactlyOnce) {
  // Before: set_mode during a capture left the recording running, so the store
  // got a capture marked complete holding idle or render samples.
  CoreHarness h;
  h.start_capture(kLongRun);
  h.run(100);
  h.command(CoreCommand::SetMode, Mode::Render);
  h.run(100);
  h.command(CoreCommand::StopCapture);  // nothing left to stop
  h.run(10);
  int in_capture = 0, ends = 0;
  for (const LoopRecord& r : h.records) {
    if (r.recording_id == 0) continue;
    EXPECT_EQ(r.mode, Mode::Capture);
    ++in_capture;
    ends += r.end != E::none;
  }
  EXPECT_EQ(in_capture, 101);  // 100 cycles, then the one that received set_mode
  EXPECT_EQ(ends, 1);
  EXPECT_EQ(h.core().state().mode, Mode::Render);
}

TEST(CoreStateMachine, WhileAFaultIsLatchedNothingStartsAndClearingLeavesTheCoreIdle) {
  CoreHarness h;
  h.command(CoreCommand::ForceSafe);
  h.step();
  h.command(CoreCommand::SetMode, Mode::Render);
  h.start_capture(kLongRun);
  h.start_calibration(5.0);
  h.command(CoreCommand::StartRecording);
  h.run(5);
  EXPECT_EQ(h.core().state().mode, Mode::Idle);
  EXPECT_EQ(h.core().state().recording_id, 0u);
  EXPECT_FALSE(h.last_out.amp_enable);
  h.command(CoreCommand::ClearFault);
  h.run(5);
  EXPECT_EQ(h.core().state().faults, 0u);
  EXPECT_EQ(h.core().state().mode, Mode::Idle);
  h.start_capture(kLongRun);
  h.run(2);
  EXPECT_EQ(h.core().state().mode, Mode::Capture);
}

}  // namespace
}  // namespace knoblab::hapticd
