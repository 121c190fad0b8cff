// The daemon as it runs: the paced realtime loop over the sim DAQ and
// in-process lines, the ring, the writer, the store.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/control/client.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/sim/presets.hpp"
#include "knoblab/store/store.hpp"
#include "shared_host.hpp"
#include "temp_db.hpp"

namespace knoblab::hapticd {
namespace {

using testing::TempDb;

struct Rig {
  hal::MemoryLines* lines = nullptr;  // owned by the daemon
  std::unique_ptr<Daemon> daemon;
  std::thread loop;
  rt::LoopResult timing;

  // With `socket`, hapticd's control server listens there.
  Rig(const std::filesystem::path& db, const char* knob, const std::string& socket = {}) {
    sim::PlantConfig plant;
    plant.knob = *sim::presets::knob(knob);
    plant.initial_angle = 0.13;  // on a detent flank, so rendering pushes
    auto daq = std::make_unique<capture::SimDaq>(plant, 10000.0);
    DaemonConfig cfg;
    cfg.core.rate_hz = 10000.0;
    cfg.core.calibration = daq->calibration();
    cfg.db = db;
    cfg.knob = knob;
    cfg.socket_path = socket;
    shared_host::configure(cfg);
    auto l = std::make_unique<hal::MemoryLines>(false);
    lines = l.get();
    daemon = std::make_unique<Daemon>(cfg, std::move(daq), std::move(l));
    loop = std::thread([this] { timing = daemon->run(); });
  }
  ~Rig() {
    daemon->stop();
    loop.join();
    shared_host::report_timing(timing);
  }
  std::vector<FinishedRecording> wait_finished(std::chrono::seconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      auto f = daemon->finished();
      if (!f.empty()) return f;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return {};
  }
};

// Acceptance: 6 s of the moderate-detents knob at 10 kHz through the real
// loop; the store holds exactly 60 000 samples per channel, none dropped.
TEST(Daemon, CapturesSixSecondsAtTenKilohertzWithoutLoss) {
  TempDb db;
  {
    Rig rig(db.path(), "moderate-detents");
    capture::CaptureConfig cc;  // Table 3 spatial sweep, thesis PID
    std::string why;
    ASSERT_TRUE(rig.daemon->start_capture(cc, 6.0, "moderate-detents", why)) << why;
    const auto f = rig.wait_finished(std::chrono::seconds(30));
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].samples, 60000);
    EXPECT_TRUE(f[0].complete);
    EXPECT_EQ(rig.daemon->ring_dropped(), 0u);
  }
  store::Store s = store::Store::open(db.path());
  const auto caps = s.list_captures();
  ASSERT_EQ(caps.size(), 1u);
  EXPECT_EQ(caps[0].status, "complete");
  EXPECT_EQ(caps[0].source, "hapticd");
  EXPECT_EQ(caps[0].knob, "moderate-detents");
  const interchange::Capture c = s.load_samples(caps[0].id);
  for (const auto* ch : {&c.t, &c.theta, &c.omega, &c.alpha, &c.torque, &c.command})
    EXPECT_EQ(ch->size(), 60000u);
  for (std::size_t i = 0; i < c.t.size(); ++i) ASSERT_EQ(c.t[i], static_cast<double>(i) * (1.0 / 10000.0));
  // The stimulus really moved the knob (a ±1 rad swept sine about where it
  // stood, which is in a detent rather than at zero).
  double lo = 0, hi = 0;
  for (double th : c.theta) lo = std::min(lo, th - c.theta[0]), hi = std::max(hi, th - c.theta[0]);
  EXPECT_LT(lo, -0.9);
  EXPECT_GT(hi, 0.9);
}

// A study trial that spans a mode change (the kiosk's home tap, the
// library's "Feel it"): idle stamps t from the daemon's start, render from
// when it was entered, and the render part was once refused as out of order
// (10 002 of 35 001 records stored). The recording has one clock, from its
// first record: every record taken is stored, a cycle apart.
TEST(Daemon, ARecordingAcrossIdleAndRenderStoresEveryRecordTakenOnOneClock) {
  TempDb db;
  std::int64_t capture_id = 0;
  std::int64_t samples = 0;
  {
    Rig rig(db.path(), "moderate-detents");
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // idle's clock is well past 0
    CoreCommand c;
    c.kind = CoreCommand::StartRecording;
    ASSERT_TRUE(rig.daemon->post(c));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    c.kind = CoreCommand::SetMode;
    c.mode = Mode::Render;
    ASSERT_TRUE(rig.daemon->post(c));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    c.mode = Mode::Idle;
    ASSERT_TRUE(rig.daemon->post(c));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    c.kind = CoreCommand::StopRecording;
    ASSERT_TRUE(rig.daemon->post(c));
    const auto f = rig.wait_finished(std::chrono::seconds(10));
    ASSERT_EQ(f.size(), 1u);
    EXPECT_TRUE(f[0].complete) << f[0].end_reason;
    capture_id = f[0].capture_id;
    samples = f[0].samples;
  }
  store::Store s = store::Store::open(db.path());
  const interchange::Capture c = s.load_samples(capture_id);
  ASSERT_EQ(static_cast<std::int64_t>(c.size()), samples);
  ASSERT_GT(c.size(), 5000u);  // 0.8 s of it at 10 kHz, at the least
  std::size_t rendered = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    ASSERT_EQ(c.t[i], static_cast<double>(i) * (1.0 / 10000.0)) << i;
    if (c.flags[i] & interchange::kAmpEnabled) ++rendered;
  }
  EXPECT_GT(rendered, 1000u) << "the render part is in it";
  EXPECT_LT(rendered, c.size() - 1000u) << "and the idle parts on both sides";
}

// Acceptance: the e-stop pulled mid-render zeroes the torque command in the
// same or the next cycle and drops amplifier enable, visibly in the samples.
TEST(Daemon, EstopMidRenderIsVisibleInTheRecordedSamples) {
  TempDb db;
  std::int64_t capture_id = 0;
  {
    Rig rig(db.path(), "moderate-detents");
    CoreCommand c;
    c.kind = CoreCommand::SetRender;
    c.immediate = true;
    c.render.B_vel = 0.02;
    c.render.A_pos = 0.04;
    c.render.P_pos = 1.0 / 12.0;
    ASSERT_TRUE(rig.daemon->post(c));
    c.kind = CoreCommand::SetMode;
    c.mode = Mode::Render;
    ASSERT_TRUE(rig.daemon->post(c));
    c.kind = CoreCommand::StartRecording;
    ASSERT_TRUE(rig.daemon->post(c));
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    rig.lines->press_estop();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_FALSE(rig.lines->amp_enable());
    c.kind = CoreCommand::StopRecording;
    ASSERT_TRUE(rig.daemon->post(c));
    const auto f = rig.wait_finished(std::chrono::seconds(10));
    ASSERT_EQ(f.size(), 1u);
    capture_id = f[0].capture_id;
    EXPECT_EQ(rig.daemon->core().state().faults, kFaultEstop);
  }
  store::Store s = store::Store::open(db.path());
  const interchange::Capture c = s.load_samples(capture_id);
  ASSERT_GT(c.size(), 1000u);
  std::size_t first = c.size();
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.flags[i] & interchange::kEstopActive) {
      first = i;
      break;
    }
  ASSERT_LT(first, c.size()) << "the e-stop never shows in the samples";
  ASSERT_GT(first, 100u);
  // Before: rendering, amplifier on, a torque commanded.
  int driving = 0;
  for (std::size_t i = first - 100; i < first; ++i) {
    EXPECT_TRUE(c.flags[i] & interchange::kAmpEnabled) << i;
    driving += c.command[i] != 0.0;
  }
  EXPECT_GT(driving, 0);
  // From that very cycle on: zero command, amplifier off, fault latched.
  for (std::size_t i = first; i < c.size(); ++i) {
    ASSERT_EQ(c.command[i], 0.0) << i;
    ASSERT_FALSE(c.flags[i] & interchange::kAmpEnabled) << i;
    ASSERT_TRUE(c.flags[i] & interchange::kFaultLatched) << i;
  }
}

template <typename What>
bool eventually(What what, std::chrono::milliseconds timeout = std::chrono::milliseconds(5000)) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!what()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

// The capture button as the kiosk sees it: each press a capture_button event
// with the count since start and how many are new, the count in get_state,
// and nothing started by hapticd itself.
TEST(Daemon, CaptureButtonPressesReachASubscribedClientAndGetState) {
  TempDb db;
  const std::string socket = (db.dir / "h.sock").string();
  Rig rig(db.path(), "moderate-detents", socket);
  // run() opens the socket before the loop's first cycle.
  ASSERT_TRUE(eventually([&] { return rig.daemon->core().state().cycles > 0; }));
  control::Client c(socket, std::chrono::seconds(5));
  c.hello();
  c.call("subscribe", {{"events", {"capture_button"}}});
  EXPECT_EQ(c.call("get_state").at("capture_button_presses"), 0);

  rig.lines->click_capture_button();
  auto e = c.wait_event(std::chrono::seconds(5));
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->name, "capture_button");
  EXPECT_EQ(e->data, nlohmann::json({{"presses", 1}, {"new", 1}}));
  rig.lines->click_capture_button();
  e = c.wait_event(std::chrono::seconds(5));
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->data, nlohmann::json({{"presses", 2}, {"new", 1}}));

  // Presses quicker than the events: however they are grouped, "new" adds
  // up to the presses made and "presses" to the total.
  for (int i = 0; i < 3; ++i) rig.lines->click_capture_button();
  std::uint64_t added = 0, total = 2;
  while (total < 5) {
    e = c.wait_event(std::chrono::seconds(5));
    ASSERT_TRUE(e.has_value()) << "after " << total << " presses";
    added += e->data.at("new").get<std::uint64_t>();
    total = e->data.at("presses").get<std::uint64_t>();
  }
  EXPECT_EQ(total, 5u);
  EXPECT_EQ(added, 3u);
  EXPECT_FALSE(c.wait_event(std::chrono::milliseconds(200)).has_value()) << "no press, no event";

  const nlohmann::json state = c.call("get_state");
  EXPECT_EQ(state.at("capture_button_presses"), 5);
  EXPECT_EQ(state.at("mode"), "idle") << "a press starts nothing in hapticd";
  EXPECT_EQ(state.at("recording"), false);
}

// Samples the LED every few milliseconds until `done` or `timeout`: how often
// it was seen lit and dark.
struct LedSeen {
  int on = 0, off = 0;
};
template <typename Done>
LedSeen watch_led(const hal::MemoryLines& lines, std::chrono::milliseconds timeout, Done done) {
  LedSeen seen;
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end && !done(seen)) {
    (lines.status_led() ? seen.on : seen.off)++;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return seen;
}

TEST(Daemon, StatusLedIsOnWhenReadyBlinksWhileACaptureRecordsAndIsOffAfterTheEstop) {
  TempDb db;
  Rig rig(db.path(), "moderate-detents");
  ASSERT_TRUE(eventually([&] { return rig.daemon->core().state().cycles > 100; }));
  const auto never = [](const LedSeen&) { return false; };
  LedSeen idle = watch_led(*rig.lines, std::chrono::milliseconds(300), never);
  EXPECT_GT(idle.on, 0);
  EXPECT_EQ(idle.off, 0) << "steady on while idle";

  capture::CaptureConfig cc;
  std::string why;
  ASSERT_TRUE(rig.daemon->start_capture(cc, 30.0, "moderate-detents", why)) << why;
  ASSERT_TRUE(eventually([&] { return rig.daemon->core().state().mode == Mode::Capture; }));
  // About a second (two blinks at 2 Hz); longer if the loop runs late here.
  const LedSeen capturing = watch_led(*rig.lines, std::chrono::seconds(5), [&](const LedSeen& s) {
    return s.on + s.off >= 200 && s.on > 20 && s.off > 20;
  });
  EXPECT_GT(capturing.on, 20) << "lit part of the time while capturing";
  EXPECT_GT(capturing.off, 20) << "dark part of the time while capturing";
  EXPECT_EQ(rig.daemon->core().state().mode, Mode::Capture);

  rig.lines->press_estop();
  ASSERT_TRUE(eventually([&] { return (rig.daemon->core().state().faults & kFaultEstop) != 0; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(5));  // past the cycle that latched it, LED written
  const LedSeen estop = watch_led(*rig.lines, std::chrono::milliseconds(600), never);
  EXPECT_EQ(estop.on, 0) << "off while the e-stop is latched";
  EXPECT_GT(estop.off, 0);
  ASSERT_EQ(rig.wait_finished(std::chrono::seconds(10)).size(), 1u);  // the capture, cut by the fault
}

}  // namespace
}  // namespace knoblab::hapticd

#include "knoblab/modbus/sim_server.hpp"

namespace knoblab::hapticd {
namespace {

std::uint32_t wait_for_faults(Daemon& d, std::uint32_t bits, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (d.core().state().faults & bits) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return d.core().state().faults;
}

// Acceptance: against knoblab-modbus-sim over TCP loopback, biometrics arrive
// at 32 Hz into the store; an amplifier fault or a disconnect puts the loop
// in the safe state.
TEST(Daemon, ModbusBiometricsAtThirtyTwoHertzAndAmplifierFaultsGoSafe) {
  modbus::SimConfig sc;
  sc.port = 0;
  modbus::SimServer server(sc);
  std::string error;
  ASSERT_TRUE(server.start(&error)) << error;

  TempDb db;
  sim::PlantConfig plant;
  plant.knob = *sim::presets::knob("moderate-detents");
  auto daq = std::make_unique<capture::SimDaq>(plant, 10000.0);
  DaemonConfig cfg;
  cfg.core.rate_hz = 10000.0;
  cfg.core.calibration = daq->calibration();
  cfg.db = db.path();
  shared_host::configure(cfg);
  modbus::PollerConfig pc;
  pc.amplifier.host = pc.biometrics.host = "127.0.0.1";
  pc.amplifier.port = pc.biometrics.port = server.port();
  // On a busy shared host without an RT kernel even the poller's SCHED_FIFO
  // threads can wait longer than the default 50 ms (sized for the appliance).
  pc.comms_timeout = pc.biometrics_timeout = modbus::Millis{400};
  cfg.modbus = pc;
  Daemon daemon(cfg, std::move(daq), std::make_unique<hal::MemoryLines>(false));
  rt::LoopResult timing;
  std::thread loop([&] { timing = daemon.run(); });

  capture::CaptureConfig cc;
  std::string why;
  ASSERT_TRUE(daemon.start_capture(cc, 3.0, "moderate-detents", why)) << why;
  std::vector<FinishedRecording> f;
  for (int i = 0; i < 500 && f.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    f = daemon.finished();
  }
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(daemon.core().state().faults, 0u);

  // An amplifier fault, then a lost link: each latches the safe state.
  const auto injected = std::chrono::steady_clock::now();
  server.set_amp_fault(1);
  EXPECT_TRUE(wait_for_faults(daemon, kFaultAmplifier, std::chrono::milliseconds(1000)) & kFaultAmplifier);
  // A figure, not a gate (the host is not realtime): the poll period is 10 ms,
  // and this wait itself polls every 5 ms.
  std::printf("[ figure   ] amplifier fault latched within %.1f ms of its injection\n",
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - injected).count());
  server.set_amp_fault(0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_TRUE(daemon.clear_faults());
  for (int i = 0; i < 100 && daemon.core().state().faults != 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(daemon.core().state().faults, 0u);
  server.drop_connections(std::chrono::milliseconds(1000));
  EXPECT_TRUE(wait_for_faults(daemon, kFaultAmpComms, std::chrono::milliseconds(1000)) & kFaultAmpComms);

  daemon.stop();
  loop.join();
  server.stop();
  shared_host::report_timing(timing);

  store::Store s = store::Store::open(db.path());
  const auto bio = s.load_biometrics(f[0].capture_id);
  EXPECT_NEAR(static_cast<double>(bio.size()), 3.0 * 32.0, 4.0);  // 32 Hz over 3 s
  for (std::size_t i = 1; i < bio.size(); ++i) {
    EXPECT_EQ(bio[i].seq, bio[i - 1].seq + 1);  // none missed, none twice
    EXPECT_NEAR(bio[i].t - bio[i - 1].t, 1.0 / 32.0, 0.03);
  }
  ASSERT_FALSE(bio.empty());
  EXPECT_GE(bio.front().t, -0.05);
  EXPECT_LE(bio.back().t, 3.05);
}

}  // namespace
}  // namespace knoblab::hapticd
