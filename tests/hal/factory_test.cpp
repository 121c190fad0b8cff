#include "knoblab/hal/factory.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fake_comedi.hpp"
#include "knoblab/capture/sim_daq.hpp"
#include "knoblab/hal/comedi_daq.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hal/shared_hand_channel.hpp"
#include "test_util.hpp"

namespace knoblab::hal {
namespace {

using test::error_of;
using test::TempDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

nlohmann::json json(const char* text) { return nlohmann::json::parse(text); }

TEST(MakeDaq, SimBackendRunsTheChosenKnob) {
  auto daq = make_daq(json(R"({"backend": "sim", "knob": "subtle-detents", "rate_hz": 10000, "seed": 7})"));
  auto* sim = dynamic_cast<capture::SimDaq*>(daq.get());
  ASSERT_NE(sim, nullptr);
  EXPECT_EQ(sim->plant().config().seed, 7u);
  // Drive it for 0.1 s: the knob turns, so the encoder moves.
  capture::DaqInputs in;
  for (int i = 0; i < 1000; ++i) {
    EXPECT_EQ(daq->read(in), capture::IoStatus::ok);
    EXPECT_EQ(daq->write({.motor_command_V = 6.0, .amp_enable = true}), capture::IoStatus::ok);
  }
  EXPECT_GT(in.encoder_counts, 0);
}

TEST(MakeDaq, SimRateDefaultsToTheDaemonsTenKilohertz) {
  // hapticd's built-in default config names only the backend and the knob.
  auto daq = make_daq(json(R"({"backend": "sim", "knob": "moderate-detents"})"));
  auto* sim = dynamic_cast<capture::SimDaq*>(daq.get());
  ASSERT_NE(sim, nullptr);
  capture::DaqInputs in;
  for (int i = 0; i < 10; ++i) EXPECT_EQ(daq->read(in), capture::IoStatus::ok);
  EXPECT_NEAR(sim->plant().state().t, 10 * 1e-4, 1e-12);
}

TEST(MakeDaq, SimErrorsNameTheKey) {
  EXPECT_EQ(error_of<ConfigError>([] { make_daq(json(R"({"backend": "sim", "rate_hz": 1000})")); }),
            "daq.knob: required key is missing");
  EXPECT_THAT(error_of<ConfigError>([] { make_daq(json(R"({"backend": "sim", "knob": "brass", "rate_hz": 1000})")); }),
              AllOf(HasSubstr("daq.knob: unknown knob preset \"brass\""), HasSubstr("subtle-detents")));
  EXPECT_THAT(error_of<ConfigError>(
                  [] { make_daq(json(R"({"backend": "sim", "knob": "subtle-detents", "rate_hz": 0})")); }),
              HasSubstr("daq.rate_hz: must be in"));
  EXPECT_THAT(error_of<ConfigError>([] {
                make_daq(json(R"({"backend": "sim", "knob": "subtle-detents", "rate_hz": 1000, "sede": 1})"));
              }),
              HasSubstr("daq.sede: unknown key"));
}

TEST(MakeDaq, ASimHandTurnsTheKnobAlongItsPathWithTheMotorOff) {
  auto daq = make_daq(json(R"({"backend": "sim", "knob": "moderate-detents", "rate_hz": 1000,
      "hand": {"amplitude_rad": 0.5, "frequency_hz": 0.5}})"));
  auto* sim = dynamic_cast<capture::SimDaq*>(daq.get());
  ASSERT_NE(sim, nullptr);
  capture::DaqInputs in;
  double worst = 0.0, furthest = 0.0;
  for (int i = 0; i < 2000; ++i) {  // one period
    EXPECT_EQ(daq->read(in), capture::IoStatus::ok);
    const double t = sim->plant().state().t, theta = sim->plant().state().knob_angle;
    worst = std::max(worst, std::abs(theta - 0.5 * std::sin(M_PI * t)));
    furthest = std::max(furthest, std::abs(theta));
  }
  EXPECT_GT(furthest, 0.45);
  // Behind the path by what the knob's friction and detents (≈ 30 mN·m) bend the grip.
  EXPECT_LT(worst, 0.05);
  EXPECT_THAT(error_of<ConfigError>([] {
                make_daq(json(R"({"backend": "sim", "knob": "moderate-detents", "hand": {"amplitude": 1}})"));
              }),
              HasSubstr("daq.hand.amplitude: unknown key"));
}

TEST(MakeDaq, AGuidedHandIsSteeredThroughItsSharedMemoryChannelByAnotherParty) {
  const std::string name = "/knoblab-factory-test-hand-" + std::to_string(::getpid());
  const std::string config =
      R"({"backend": "sim", "knob": "study3-not-rendered", "rate_hz": 1000, "hand": {"channel": ")" + name + R"("}})";
  auto daq = make_daq(json(config.c_str()));
  auto* sim = dynamic_cast<capture::SimDaq*>(daq.get());
  ASSERT_NE(sim, nullptr);
  // The participant's side: the same channel, opened by name (as knoblab study simulate does).
  const SharedHandChannel participant(name);
  participant.channel().send({0.7, 0.3, 1.0, 0.01});
  capture::DaqInputs in;
  for (int i = 0; i < 600; ++i) ASSERT_EQ(daq->read(in), capture::IoStatus::ok);
  EXPECT_NEAR(sim->plant().state().knob_angle, 0.7, 0.01);
  ::shm_unlink(name.c_str());
  EXPECT_THAT(error_of<ConfigError>([] {
                make_daq(json(R"({"backend": "sim", "knob": "moderate-detents", "hand": {"channel": "no-slash"}})"));
              }),
              HasSubstr("daq.hand.channel: hand channel name 'no-slash' must be"));
  EXPECT_THAT(error_of<ConfigError>([] {
                make_daq(json(R"({"backend": "sim", "knob": "moderate-detents",
                                  "hand": {"channel": "/x", "amplitude_rad": 1}})"));
              }),
              HasSubstr("daq.hand.amplitude_rad: unknown key"));
}

TEST(MakeDaq, BackendMustBeNamedAndKnown) {
  EXPECT_EQ(error_of<ConfigError>([] { make_daq(json(R"({"knob": "subtle-detents"})")); }),
            "daq.backend: required key is missing");
  EXPECT_EQ(error_of<ConfigError>([] { make_daq(json(R"({"backend": "labjack"})"), "hapticd.daq"); }),
            "hapticd.daq.backend: unknown backend \"labjack\" (use sim or comedi)");
  EXPECT_EQ(error_of<ConfigError>([] { make_daq(json(R"(["sim"])")); }), "daq: expected an object, got [\"sim\"]");
}

TEST(MakeDaq, ComediBackendOpensTheConfiguredBoard) {
  test::FakeComedi api;
  api.boards["/dev/comedi0"] = test::das1602();
  auto daq = make_daq(json(R"({"backend": "comedi", "device": "/dev/comedi0",
      "torque": {"channel": 0, "range_V": [-1.25, 1.25]}, "accel": {"channel": 1},
      "motor": {"channel": 0}, "encoder": {"channel": 0}})"),
                      "daq", api);
  EXPECT_NE(dynamic_cast<ComediDaq*>(daq.get()), nullptr);
  EXPECT_EQ(api.open_devices, 1);
}

TEST(MakeDaq, ComediConfigErrorsComeBeforeTheDeviceIsOpened) {
  test::FakeComedi api;
  EXPECT_EQ(error_of<ConfigError>([&] { make_daq(json(R"({"backend": "comedi", "device": "/dev/comedi0"})"), "daq", api); }),
            "daq.torque: required key is missing");
  EXPECT_TRUE(api.log.empty());
}

TEST(MakeDaq, RealComediWithoutABoardFailsWithThePath) {
  if (std::filesystem::exists("/dev/comedi0")) GTEST_SKIP() << "this machine has /dev/comedi0";
  EXPECT_EQ(error_of<std::runtime_error>([] {
              make_daq(json(R"({"backend": "comedi", "device": "/dev/comedi0", "torque": {"channel": 0},
                  "accel": {"channel": 1}, "motor": {"channel": 0}, "encoder": {"channel": 0}})"));
            }),
            "cannot open Comedi device /dev/comedi0: No such file or directory");
}

TEST(MakeLines, MemoryBackendStartsAssertedUnlessTold) {
  auto lines = make_lines(json(R"({"backend": "memory"})"));
  ASSERT_NE(dynamic_cast<MemoryLines*>(lines.get()), nullptr);
  DigitalInputs in;
  in.estop = false;
  EXPECT_EQ(lines->read(in), capture::IoStatus::ok);
  EXPECT_TRUE(in.estop);
  lines = make_lines(json(R"({"backend": "memory", "estop": "released"})"));
  EXPECT_EQ(lines->read(in), capture::IoStatus::ok);
  EXPECT_FALSE(in.estop);
  EXPECT_THAT(error_of<ConfigError>([] { make_lines(json(R"({"backend": "memory", "estop": "off"})")); }),
              HasSubstr("lines.estop: must be \"asserted\" or \"released\""));
}

TEST(MakeLines, GpiodBackendReachesTheHardwareLookup) {
  TempDir dir;
  nlohmann::json j = json(R"({"backend": "gpiod", "chip": "auto",
      "lines": {"amp_enable": "AMP_EN", "estop": "ESTOP_N", "capture_button": "FOOTSW", "status_led": "LED_STATUS"}})");
  j["device_dir"] = dir.path().string();
  EXPECT_THAT(error_of<std::runtime_error>([&] { make_lines(j); }),
              HasSubstr("GPIO line \"AMP_EN\" (amp_enable) not found: no GPIO chips (gpiochip*) in " + dir.path().string()));
  j.erase("lines");
  EXPECT_EQ(error_of<ConfigError>([&] { make_lines(j); }), "lines.lines: required key is missing");
}

TEST(MakeLines, UnknownBackendIsNamed) {
  EXPECT_EQ(error_of<ConfigError>([] { make_lines(json(R"({"backend": "sysfs"})")); }),
            "lines.backend: unknown backend \"sysfs\" (use gpiod or memory)");
}

TEST(ConfigText, BadJsonNamesItsOriginAndPosition) {
  EXPECT_THAT(error_of<ConfigError>([] { parse_config_text("{\"backend\": \"sim\",\n  oops}", "hapticd.json"); }),
              AllOf(HasSubstr("hapticd.json: invalid JSON"), HasSubstr("line 2")));
}

TEST(ConfigText, LoadsAFileOrNamesIt) {
  TempDir dir;
  const auto path = dir.touch("hapticd.json", R"({"daq": {"backend": "sim", "knob": "high-friction", "rate_hz": 1000}})");
  const nlohmann::json config = load_config_file(path);
  EXPECT_NE(make_daq(config.at("daq"), "daq"), nullptr);
  const auto missing = dir.path() / "nope.json";
  EXPECT_EQ(error_of<ConfigError>([&] { load_config_file(missing); }),
            missing.string() + ": cannot read the configuration file");
}


// A document nested a million levels deep: the parser and everything that
// walks what it builds recurse, and the reader segfaulted on it.
std::string nested_a_million_deep() {
  return "{\"daq\": " + std::string(1000000, '[') + std::string(1000000, ']') + "}";
}

TEST(Factory, AConfigNestedBeyondSixtyFourLevelsIsRefusedBeforeItIsParsed) {
  try {
    parse_config_text(nested_a_million_deep(), "hapticd.json");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("hapticd.json: invalid JSON: nested deeper than 64 levels at byte 72"));
  }
  // A bracket in a string is text, not nesting.
  EXPECT_NO_THROW(parse_config_text(R"({"daq": {"knob": "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[\"{{"}})",
                                    "hapticd.json"));
}

}  // namespace
}  // namespace knoblab::hal
