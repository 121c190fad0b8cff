// HapticCore::cycle runs in the realtime loop: whatever the mode, whatever
// command arrives, it must never allocate. Every global operator new is
// counted while a flag is up, around cycle() and the status LED's level
// (what the daemon's loop does with the record) only; posting a command is
// the non-realtime side's business.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "alloc_counter.hpp"
#include "core_harness.hpp"
#include "knoblab/hapticd/status_led.hpp"

using knoblab::test::g_allocations;
using knoblab::test::g_counting;

namespace knoblab::hapticd {
namespace {

using testing::CoreHarness;

// The harness's core and DAQ, with allocations counted inside cycle() only
// (the harness's own step() keeps a log of records, which allocates).
class Rig : public CoreHarness {
 public:
  void run(int n, CycleContext context = {}) {
    for (int i = 0; i < n; ++i) {
      capture::DaqInputs in;
      context.io_ok = daq().read(in) == capture::IoStatus::ok;
      capture::DaqOutputs out;
      LoopRecord rec;
      g_counting = true;
      core().cycle(in, context, out, rec);
      (void)status_led(rec, kRate);
      g_counting = false;
      (void)daq().write(out);
    }
  }
};

TEST(CycleAllocations, TheCounterSeesAnAllocation) {
  g_allocations = 0;
  g_counting = true;
  auto p = std::make_unique<int>(3);
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 1);
}

TEST(CycleAllocations, NoModeNoTransitionAndNoCommandAllocatesInTheCycle) {
  Rig rig;
  rig.run(10);  // first cycles: nothing lazily built later may hide here
  g_allocations = 0;

  rig.run(100);  // idle
  CoreCommand model;
  model.kind = CoreCommand::SetRender;
  model.render.M_acc = 5e-5;
  model.render.B_vel = 5e-4;
  model.render.A_pos = 0.01;
  model.render.P_pos = 1.0 / 12.0;
  model.render.stick = true;
  model.render.dv = 0.05;
  model.render.D_neg = model.render.D_pos = 0.005;
  rig.post(model);
  rig.command(CoreCommand::SetMode, Mode::Render);
  rig.run(200);
  model.render.A_pos = 0.02;  // a slider drag while rendering
  rig.post(model);
  rig.command(CoreCommand::StartRecording);
  rig.run(200);
  rig.command(CoreCommand::StopRecording);
  rig.run(10);

  rig.post(rig.capture_command(300));  // a capture that runs to its end
  rig.run(400);
  rig.post(rig.capture_command(100000));  // one stopped by a mode change
  rig.run(100);
  rig.command(CoreCommand::SetMode, Mode::Render);
  rig.run(10);
  rig.command(CoreCommand::SetMode, Mode::Idle);
  rig.run(10);

  for (CalibrationKind k : {CalibrationKind::Spatial, CalibrationKind::Torque, CalibrationKind::AccelGain,
                            CalibrationKind::Gravity}) {
    // Sweeps of 0.05 s; gravity a revolution in 2 s, slow enough for the velocity limit.
    rig.post(rig.calibration_command(k == CalibrationKind::Gravity ? 2.0 : 0.05, k));
    rig.run(2000);
  }
  rig.command(CoreCommand::StopCapture);  // gravity is still running: stopped early
  rig.run(10);

  rig.post(rig.capture_command(100000));  // a fault ends it, then is cleared
  rig.run(50);
  CycleContext estop;
  estop.lines.estop = true;
  rig.run(5, estop);
  rig.command(CoreCommand::ClearFault);
  rig.command(CoreCommand::ForceSafe);
  rig.run(5);
  rig.command(CoreCommand::ClearFault);
  rig.run(5);

  EXPECT_EQ(rig.core().state().faults, 0u);
  EXPECT_EQ(g_allocations.load(), 0);
}

// Prototyper tiles are built (allocating) outside the loop and handed over
// whole: rendering them, replacing them while they play and clearing them
// allocates nothing in the cycle; nor does a new sensor calibration.
std::unique_ptr<TileSet> tile_set(double damping) {
  auto set = std::make_unique<TileSet>();
  const std::vector<double> x = {-3.0, 0.0, 3.0}, b = {damping, 2 * damping, damping};
  model::PositionTile p;
  p.f_vel = model::CubicSpline(x, b);
  p.theta_min = -3.0;
  p.theta_max = 3.0;
  // The torque-valued curves and the mass that joins the virtual mass.
  const std::vector<double> tau = {-0.01, 0.0, 0.01}, v = {-1.0, 0.0, 1.0}, m = {1e-5, 2e-5, 1e-5};
  p.torque_of_angle = model::CubicSpline(x, tau);
  p.torque_of_velocity = model::CubicSpline(v, tau);
  p.mass = model::CubicSpline(x, m);
  set->position.push_back(p);
  model::TimeTile t;
  const std::vector<double> ts = {0.0, 0.005, 0.01}, k = {0.0, 0.01, 0.0};
  t.f_pos = model::CubicSpline(ts, k);
  t.torque_of_time = model::CubicSpline(ts, k);
  t.duration = 0.01;
  t.loop = true;
  set->time.push_back(t);
  return set;
}

TEST(CycleAllocations, RenderingTilesSwappingThemAndRecalibratingAllocateNothingInTheCycle) {
  Rig rig;
  rig.set_render(5e-4, 0.01);
  rig.command(CoreCommand::SetMode, Mode::Render);
  rig.run(10);
  g_allocations = 0;

  ASSERT_TRUE(rig.core().load_tiles(tile_set(1e-3)));
  rig.run(500);  // the time tile loops five times
  for (int i = 0; i < 5; ++i) {  // a designer dragging a point while it plays
    auto next = tile_set(1e-3 * (i + 2));
    while (!rig.core().load_tiles(std::move(next))) rig.run(1);
    rig.run(20);  // mid-fade: the next one waits for it
  }
  while (!rig.core().load_tiles(nullptr)) rig.run(1);
  rig.run(600);  // faded out; the last set is back with the publisher
  CoreCommand cal;
  cal.kind = CoreCommand::SetSensorCalibration;
  cal.sensors = rig.daq().calibration();
  cal.sensors.C_cal *= 1.01;
  rig.post(cal);
  rig.run(10);
  EXPECT_DOUBLE_EQ(rig.core().sensor_calibration().C_cal, cal.sensors.C_cal);
  EXPECT_EQ(g_allocations.load(), 0);
}

}  // namespace
}  // namespace knoblab::hapticd
