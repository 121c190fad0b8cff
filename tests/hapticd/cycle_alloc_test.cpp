// HapticCore::cycle runs in the realtime loop: whatever the mode, whatever
// command arrives, it must never allocate. Every global operator new is
// counted while a flag is up, around cycle() only (posting a command is the
// non-realtime side's business).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hapticd/core.hpp"
#include "knoblab/sim/presets.hpp"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};

void* counted(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return counted(n); }
void* operator new[](std::size_t n) { return counted(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace knoblab::hapticd {
namespace {

constexpr double kRate = 10000.0;

class Rig {
 public:
  Rig() : daq_(plant(), kRate), core_(config(daq_)) {}

  // Runs n cycles, counting allocations inside cycle() only.
  void run(int n, CycleContext ctx = {}) {
    for (int i = 0; i < n; ++i) {
      capture::DaqInputs in;
      ctx.io_ok = daq_.read(in) == capture::IoStatus::ok;
      capture::DaqOutputs out;
      LoopRecord rec;
      g_counting = true;
      core_.cycle(in, ctx, out, rec);
      g_counting = false;
      (void)daq_.write(out);
    }
  }
  void post(const CoreCommand& c) { ASSERT_TRUE(core_.post(c)); }
  void command(CoreCommand::Kind kind, Mode mode = Mode::Idle) {
    CoreCommand c;
    c.kind = kind;
    c.mode = mode;
    post(c);
  }
  CoreCommand capture(std::int64_t cycles) const {
    CoreCommand c;
    c.kind = CoreCommand::StartCapture;
    capture::CaptureConfig cc;
    cc.rate_hz = kRate;
    c.capture = capture::CaptureController(cc);
    c.capture_cycles = cycles;
    return c;
  }
  CoreCommand calibration(CalibrationKind kind) const {
    CoreCommand c;
    c.kind = CoreCommand::StartCalibration;
    CalibrationConfig cc;
    cc.kind = kind;
    cc.rate_hz = kRate;
    cc.calibration = daq_.calibration();
    cc.sweep_seconds = 0.05;
    cc.gravity_seconds = 2.0;  // a revolution in 2 s: slow enough for the velocity limit
    c.calibration = CalibrationController(cc);
    return c;
  }
  HapticCore& core() { return core_; }

 private:
  static sim::PlantConfig plant() {
    sim::PlantConfig p;
    p.knob = *sim::presets::knob("moderate-detents");
    return p;
  }
  static CoreConfig config(const capture::SimDaq& daq) {
    CoreConfig c;
    c.rate_hz = kRate;
    c.calibration = daq.calibration();
    return c;
  }
  capture::SimDaq daq_;
  HapticCore core_;
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

  rig.post(rig.capture(300));  // a capture that runs to its end
  rig.run(400);
  rig.post(rig.capture(100000));  // one stopped by a mode change
  rig.run(100);
  rig.command(CoreCommand::SetMode, Mode::Render);
  rig.run(10);
  rig.command(CoreCommand::SetMode, Mode::Idle);
  rig.run(10);

  for (CalibrationKind k : {CalibrationKind::Spatial, CalibrationKind::Torque, CalibrationKind::AccelGain,
                            CalibrationKind::Gravity}) {
    rig.post(rig.calibration(k));
    rig.run(2000);
  }
  rig.command(CoreCommand::StopCapture);  // gravity is still running: stopped early
  rig.run(10);

  rig.post(rig.capture(100000));  // a fault ends it, then is cleared
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

}  // namespace
}  // namespace knoblab::hapticd
