// The daemon's own safety paths with the real paced loop: an exception in
// the loop, a dead encoder, render parameters beyond the device.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hapticd/control_handler.hpp"
#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/sim/presets.hpp"
#include "shared_host.hpp"

namespace knoblab::hapticd {
namespace {

using namespace std::chrono_literals;

// The simulated camera, with a read that throws once a test asks it to
// (a driver bug), and a record of what was last written.
class ThrowingDaq final : public capture::Daq {
 public:
  explicit ThrowingDaq(sim::PlantConfig p) : sim_(p, 10000.0) {}
  capture::IoStatus read(capture::DaqInputs& in) override {
    if (throw_now.load()) throw std::runtime_error("driver bug");
    return sim_.read(in);
  }
  capture::IoStatus write(const capture::DaqOutputs& out) override {
    last_command_V.store(out.motor_command_V);
    last_enable.store(out.amp_enable);
    return sim_.write(out);
  }
  capture::SensorCalibration calibration() const { return sim_.calibration(); }
  std::atomic<bool> throw_now{false};
  std::atomic<double> last_command_V{0.0};
  std::atomic<bool> last_enable{false};

 private:
  capture::SimDaq sim_;
};

sim::PlantConfig on_a_detent_flank() {
  sim::PlantConfig plant;
  plant.knob = *sim::presets::knob("moderate-detents");
  plant.initial_angle = 0.13;  // rendering detents pushes here
  return plant;
}

DaemonConfig config_for(const capture::SensorCalibration& cal) {
  DaemonConfig cfg;
  cfg.core.rate_hz = 10000.0;
  cfg.core.calibration = cal;
  shared_host::configure(cfg);
  return cfg;
}

void render_detents(Daemon& d) {
  CoreCommand c;
  c.kind = CoreCommand::SetRender;
  c.immediate = true;
  c.render.A_pos = 0.02;
  c.render.P_pos = 1.0 / 12.0;
  ASSERT_TRUE(d.post(c));
  c.kind = CoreCommand::SetMode;
  c.mode = Mode::Render;
  ASSERT_TRUE(d.post(c));
}

bool eventually(const std::function<bool()>& what, std::chrono::milliseconds timeout = 3000ms) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (what()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return what();
}

TEST(DaemonSafety, AnExceptionInTheLoopLeavesTheMotorSafeAndRunReturnsIt) {
  auto daq = std::make_unique<ThrowingDaq>(on_a_detent_flank());
  ThrowingDaq* raw = daq.get();
  auto lines = std::make_unique<hal::MemoryLines>(false);
  hal::MemoryLines* l = lines.get();
  auto daemon = std::make_unique<Daemon>(config_for(raw->calibration()), std::move(daq), std::move(lines));
  render_detents(*daemon);
  auto ran = std::async(std::launch::async, [&] { return daemon->run(); });
  ASSERT_TRUE(eventually([&] { return l->amp_enable() && raw->last_command_V.load() != 0.0; }));

  raw->throw_now.store(true);
  // Before the guard, run() skipped the safe-state writes and ~Daemon then
  // waited forever for the writer thread.
  ASSERT_EQ(ran.wait_for(5s), std::future_status::ready);
  EXPECT_THROW(ran.get(), std::runtime_error);
  EXPECT_FALSE(l->amp_enable());
  EXPECT_FALSE(raw->last_enable.load());
  EXPECT_EQ(raw->last_command_V.load(), 0.0);
  auto destroyed = std::async(std::launch::async, [&] { daemon.reset(); });
  EXPECT_EQ(destroyed.wait_for(5s), std::future_status::ready);
}

TEST(DaemonSafety, ADeadEncoderLatchesIoAndDropsTheAmplifierEnable) {
  auto daq = std::make_unique<capture::SimDaq>(on_a_detent_flank(), 10000.0);
  capture::SimDaq* sim = daq.get();
  auto lines = std::make_unique<hal::MemoryLines>(false);
  hal::MemoryLines* l = lines.get();
  Daemon daemon(config_for(sim->calibration()), std::move(daq), std::move(lines));
  render_detents(daemon);
  rt::LoopResult timing;
  std::thread loop([&] { timing = daemon.run(); });
  EXPECT_TRUE(eventually([&] { return l->amp_enable(); }));

  sim->set_read_failure(true);  // the encoder cable pulled: the angle would freeze
  EXPECT_TRUE(eventually([&] { return (daemon.core().state().faults & kFaultIo) != 0; }));
  EXPECT_FALSE(l->amp_enable());
  EXPECT_EQ(daemon.core().state().mode, Mode::Idle);
  daemon.stop();
  loop.join();
  shared_host::report_timing(timing);
}

TEST(DaemonSafety, RenderParametersBeyondTheDeviceAreRefusedAtTheProtocolWithTheKey) {
  capture::SimDaq probe(on_a_detent_flank(), 10000.0);
  Daemon daemon(config_for(probe.calibration()), std::make_unique<capture::SimDaq>(on_a_detent_flank(), 10000.0),
                std::make_unique<hal::MemoryLines>(false));
  ControlHandler handler(daemon, {});
  auto send = [&](control::Command cmd, nlohmann::json args) {
    control::Request r;
    r.command = cmd;
    r.args = std::move(args);
    return handler.handle(r);
  };
  const control::Reply big = send(control::Command::load_model,
                                  {{"M_acc", 0.0}, {"B_vel", 0.0}, {"A_pos", 0.3}, {"P_pos", 0.1}});
  ASSERT_FALSE(big.ok);
  EXPECT_EQ(big.error.key, "A_pos");
  EXPECT_NE(big.error.message.find("torque limit of 180 mN·m"), std::string::npos) << big.error.message;

  const control::Reply stick = send(control::Command::set_params, {{"dv", 0.1}, {"D_neg", 0.25}, {"D_pos", 0.01}});
  ASSERT_FALSE(stick.ok);
  EXPECT_EQ(stick.error.key, "D_neg");

  EXPECT_TRUE(send(control::Command::load_model, {{"M_acc", 0.0}, {"B_vel", 0.0}, {"A_pos", 0.02}, {"P_pos", 0.1}}).ok);
}

TEST(DaemonSafety, WhileAFaultIsLatchedRenderAndTrialsAreRefusedWithTheFaultNamed) {
  auto daq = std::make_unique<capture::SimDaq>(on_a_detent_flank(), 10000.0);
  const capture::SensorCalibration cal = daq->calibration();
  Daemon daemon(config_for(cal), std::move(daq), std::make_unique<hal::MemoryLines>(false));
  ControlHandler handler(daemon, {});
  rt::LoopResult timing;
  std::thread loop([&] { timing = daemon.run(); });
  struct Joined {  // stops the loop however the test leaves
    Daemon& d;
    std::thread& t;
    ~Joined() {
      d.stop();
      if (t.joinable()) t.join();
    }
  } joined{daemon, loop};
  CoreCommand safe;
  safe.kind = CoreCommand::ForceSafe;
  ASSERT_TRUE(daemon.post(safe));
  ASSERT_TRUE(eventually([&] { return daemon.core().state().faults != 0; }));
  for (const auto& [cmd, args] : {std::pair{control::Command::set_mode, nlohmann::json{{"mode", "render"}}},
                                  std::pair{control::Command::start_trial,
                                            nlohmann::json{{"study", "S"}, {"participant", 1}, {"condition", "c"}}}}) {
    control::Request r;
    r.command = cmd;
    r.args = args;
    const control::Reply reply = handler.handle(r);
    ASSERT_FALSE(reply.ok);
    EXPECT_EQ(reply.error.code, control::ErrorCode::busy);
    EXPECT_NE(reply.error.message.find("commanded"), std::string::npos) << reply.error.message;
  }
  EXPECT_EQ(daemon.core().state().mode, Mode::Idle);
}

TEST(DaemonSafety, RenderParamsProblemRefusesNonFiniteAndNegativeValues) {
  const SafetyLimits limits;
  RenderParams p;
  EXPECT_FALSE(render_params_problem(p, limits));
  p.B_vel = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(render_params_problem(p, limits));
  EXPECT_EQ(render_params_problem(p, limits)->key, "B_vel");
  p.B_vel = -0.001;
  EXPECT_EQ(render_params_problem(p, limits)->key, "B_vel");
  p.B_vel = 0.0;
  p.A_pos = -0.05;  // a sign is a phase, not energy
  EXPECT_FALSE(render_params_problem(p, limits));
  p.K_vm = std::numeric_limits<double>::infinity();
  EXPECT_EQ(render_params_problem(p, limits)->key, "K_vm");
}

}  // namespace
}  // namespace knoblab::hapticd
