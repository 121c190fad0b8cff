// The modbus section of hapticd's config: both devices over their own
// transports, defaults from PollerConfig, and every mistake (typo, wrong
// type, a timeout the watchdog cannot tolerate) failing with the key's path.
#include "knoblab/hal/modbus_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "knoblab/hal/config_error.hpp"
#include "knoblab/modbus/register_map.hpp"
#include "test_util.hpp"

namespace knoblab::hal {
namespace {

using modbus::Millis;
using test::error_of;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

nlohmann::json full() {
  return nlohmann::json::parse(R"({
    "amplifier": {"transport": "tcp", "host": "10.0.0.5", "port": 1502, "unit": 3, "response_timeout_ms": 15},
    "biometrics": {"transport": "rtu", "device": "/dev/ttyUSB0", "baud": 57600, "parity": "even",
                   "data_bits": 8, "stop_bits": 2, "unit": 4, "response_timeout_ms": 30},
    "amplifier_period_ms": 5, "biometrics_period_ms": 12, "comms_timeout_ms": 40,
    "biometrics_timeout_ms": 150, "priority": 45})");
}

nlohmann::json tcp_device() { return {{"transport", "tcp"}, {"host", "127.0.0.1"}}; }

std::string error_for(const nlohmann::json& j) {
  return error_of<ConfigError>([&] { parse_modbus_config(j); });
}

std::string ms(Millis d) { return std::to_string(d.count()) + " ms"; }

TEST(ModbusConfig, ParsesBothDevicesEachOverItsOwnTransport) {
  const modbus::PollerConfig c = parse_modbus_config(full());
  EXPECT_TRUE(c.poll_amplifier);
  EXPECT_TRUE(c.poll_biometrics);
  EXPECT_EQ(c.amplifier.kind, modbus::Transport::tcp);
  EXPECT_EQ(c.amplifier.host, "10.0.0.5");
  EXPECT_EQ(c.amplifier.port, 1502);
  EXPECT_EQ(c.amplifier.unit_id, 3);
  EXPECT_EQ(c.amplifier.response_timeout, Millis{15});
  EXPECT_EQ(c.biometrics.kind, modbus::Transport::rtu);
  EXPECT_EQ(c.biometrics.device, "/dev/ttyUSB0");
  EXPECT_EQ(c.biometrics.baud, 57600u);
  EXPECT_EQ(c.biometrics.parity, modbus::Parity::even);
  EXPECT_EQ(c.biometrics.data_bits, 8);
  EXPECT_EQ(c.biometrics.stop_bits, 2);
  EXPECT_EQ(c.biometrics.unit_id, 4);
  EXPECT_EQ(c.biometrics.response_timeout, Millis{30});
  EXPECT_EQ(c.amplifier_period, Millis{5});
  EXPECT_EQ(c.biometrics_period, Millis{12});
  EXPECT_EQ(c.comms_timeout, Millis{40});
  EXPECT_EQ(c.biometrics_timeout, Millis{150});
  EXPECT_EQ(c.priority, 45);
  EXPECT_NO_THROW(modbus::Poller{c});  // what the parser accepts, the poller does
}

TEST(ModbusConfig, TheExampleInTheDocsIsValid) {  // docs/hal.md
  const modbus::PollerConfig c = parse_modbus_config(nlohmann::json::parse(R"({
    "amplifier":  {"transport": "tcp", "host": "10.0.0.5", "port": 502, "unit": 1, "response_timeout_ms": 20},
    "biometrics": {"transport": "rtu", "device": "/dev/ttyUSB0", "baud": 115200, "parity": "even",
                   "data_bits": 8, "stop_bits": 1, "unit": 2},
    "amplifier_period_ms": 10, "biometrics_period_ms": 10, "comms_timeout_ms": 50,
    "biometrics_timeout_ms": 100, "priority": 0})"));
  EXPECT_EQ(c.amplifier.kind, modbus::Transport::tcp);
  EXPECT_EQ(c.biometrics.kind, modbus::Transport::rtu);
}

TEST(ModbusConfig, UnsetKeysTakeThePollersDefaults) {
  const modbus::PollerConfig c = parse_modbus_config({{"amplifier", tcp_device()}, {"biometrics", tcp_device()}});
  const modbus::PollerConfig d;
  EXPECT_EQ(c.amplifier.port, d.amplifier.port);
  EXPECT_EQ(c.amplifier.unit_id, modbus::kDefaultAmplifierUnit);
  EXPECT_EQ(c.biometrics.unit_id, modbus::kDefaultBiometricsUnit);
  EXPECT_EQ(c.amplifier.response_timeout, d.amplifier.response_timeout);
  EXPECT_EQ(c.amplifier_period, d.amplifier_period);
  EXPECT_EQ(c.biometrics_period, d.biometrics_period);
  EXPECT_EQ(c.comms_timeout, d.comms_timeout);
  EXPECT_EQ(c.biometrics_timeout, d.biometrics_timeout);
  EXPECT_EQ(c.priority, d.priority);

  const modbus::PollerConfig rtu = parse_modbus_config(
      {{"biometrics", {{"transport", "rtu"}, {"device", "/dev/ttyS1"}}}});
  EXPECT_EQ(rtu.biometrics.baud, d.biometrics.baud);
  EXPECT_EQ(rtu.biometrics.parity, d.biometrics.parity);
  EXPECT_EQ(rtu.biometrics.data_bits, d.biometrics.data_bits);
  EXPECT_EQ(rtu.biometrics.stop_bits, d.biometrics.stop_bits);
}

TEST(ModbusConfig, EitherDeviceMayBeLeftOutButNotBoth) {
  modbus::PollerConfig c = parse_modbus_config({{"amplifier", tcp_device()}});
  EXPECT_TRUE(c.poll_amplifier);
  EXPECT_FALSE(c.poll_biometrics);
  c = parse_modbus_config({{"biometrics", tcp_device()}});
  EXPECT_FALSE(c.poll_amplifier);
  EXPECT_TRUE(c.poll_biometrics);
  EXPECT_THAT(error_for(nlohmann::json::object()), StartsWith("modbus: nothing to poll"));
  EXPECT_THAT(error_for({{"comms_timeout_ms", 50}}), StartsWith("modbus: nothing to poll"));
}

TEST(ModbusConfig, UnknownKeysAreTyposNotDefaults) {
  nlohmann::json j = full();
  j["amplifier"]["prot"] = 502;
  EXPECT_EQ(error_for(j), "modbus.amplifier.prot: unknown key (known here: host, port, response_timeout_ms, "
                          "transport, unit)");
  j = full();
  j["amplifier"]["baud"] = 9600;  // a serial setting on a TCP device
  EXPECT_THAT(error_for(j), StartsWith("modbus.amplifier.baud: unknown key"));
  j = full();
  j["biometrics"]["host"] = "10.0.0.6";  // and the reverse
  EXPECT_THAT(error_for(j), StartsWith("modbus.biometrics.host: unknown key"));
  j = full();
  j["comms_timeout"] = 50;  // without its unit
  EXPECT_THAT(error_for(j), StartsWith("modbus.comms_timeout: unknown key"));
}

TEST(ModbusConfig, MissingAndMistypedKeysAreNamed) {
  nlohmann::json j = full();
  j["amplifier"].erase("transport");
  EXPECT_EQ(error_for(j), "modbus.amplifier.transport: required key is missing");
  j = full();
  j["amplifier"].erase("host");
  EXPECT_EQ(error_for(j), "modbus.amplifier.host: required key is missing");
  j = full();
  j["biometrics"].erase("device");
  EXPECT_EQ(error_for(j), "modbus.biometrics.device: required key is missing");
  j = full();
  j["amplifier"]["transport"] = "udp";
  EXPECT_EQ(error_for(j), "modbus.amplifier.transport: unknown transport \"udp\" (use tcp or rtu)");
  j = full();
  j["amplifier"]["port"] = "502";
  EXPECT_EQ(error_for(j), "modbus.amplifier.port: expected a non-negative integer, got \"502\"");
  j = full();
  j["amplifier"]["port"] = 70000;
  EXPECT_EQ(error_for(j), "modbus.amplifier.port: must be 1..65535, got 70000");
  j = full();
  j["biometrics"]["parity"] = "evn";
  EXPECT_EQ(error_for(j), "modbus.biometrics.parity: unknown parity \"evn\" (use none, even or odd)");
  j = full();
  j["biometrics_timeout_ms"] = 0.5;
  EXPECT_EQ(error_for(j), "modbus.biometrics_timeout_ms: expected a non-negative integer, got 0.5");
  j = full();
  j["biometrics"] = "/dev/ttyUSB0";
  EXPECT_EQ(error_for(j), "modbus.biometrics: expected an object, got \"/dev/ttyUSB0\"");
  j = full();
  j["priority"] = 120;
  EXPECT_THAT(error_for(j), StartsWith("modbus.priority: must be 0"));
}

TEST(ModbusConfig, EndpointProblemsNameTheDevice) {
  nlohmann::json j = full();
  j["amplifier"]["unit"] = 0;
  EXPECT_EQ(error_for(j), "modbus.amplifier: unit id must be 1..247, got 0");
  j = full();
  j["biometrics"]["data_bits"] = 9;
  EXPECT_EQ(error_for(j), "modbus.biometrics: rtu data bits must be 5..8");
  j = full();
  j["amplifier"]["response_timeout_ms"] = 0;
  EXPECT_EQ(error_for(j), "modbus.amplifier: response timeout must be positive");
}

TEST(ModbusConfig, ATimeoutOneUnansweredRequestWouldTurnIntoAWatchdogTripFailsAtParseTime) {
  nlohmann::json j = full();
  const Millis period{j["amplifier_period_ms"].get<unsigned>()};
  const Millis comms{j["comms_timeout_ms"].get<unsigned>()};
  j["amplifier"]["response_timeout_ms"] = (comms - period).count();
  EXPECT_THAT(error_for(j), AllOf(StartsWith("modbus.amplifier.response_timeout_ms: "),
                                  HasSubstr(ms(comms - period)), HasSubstr(ms(period)), HasSubstr(ms(comms))));

  j = full();
  const Millis bio_period{j["biometrics_period_ms"].get<unsigned>()};
  const Millis bio_timeout{j["biometrics_timeout_ms"].get<unsigned>()};
  j["biometrics"]["response_timeout_ms"] = (bio_timeout - bio_period).count();
  EXPECT_THAT(error_for(j), AllOf(StartsWith("modbus.biometrics.response_timeout_ms: "),
                                  HasSubstr(ms(bio_timeout - bio_period)), HasSubstr(ms(bio_timeout))));

  j = full();
  j["biometrics_period_ms"] = 40;  // would miss 32 Hz samples
  EXPECT_THAT(error_for(j), StartsWith("modbus.biometrics_period_ms: must be 1..15 ms"));
}

TEST(ModbusConfig, DevicesOnOneRtuBusMustAgreeOnTheLine) {
  nlohmann::json j = full();
  j["amplifier"] = j["biometrics"];
  j["amplifier"]["unit"] = 1;
  EXPECT_NO_THROW(parse_modbus_config(j));
  j["amplifier"]["baud"] = 115200;
  EXPECT_THAT(error_for(j), AllOf(StartsWith("modbus.biometrics.baud: "), HasSubstr("/dev/ttyUSB0")));
  j["amplifier"]["baud"] = j["biometrics"]["baud"];
  j["amplifier"]["unit"] = j["biometrics"]["unit"];
  EXPECT_THAT(error_for(j), StartsWith("modbus.biometrics.unit: "));
}

TEST(ModbusConfig, PathsStartWithTheCallersPrefix) {
  nlohmann::json j = full();
  j["amplifier"]["prot"] = 502;
  EXPECT_THAT(error_of<ConfigError>([&] { parse_modbus_config(j, "hapticd.modbus"); }),
              StartsWith("hapticd.modbus.amplifier.prot: "));
}

}  // namespace
}  // namespace knoblab::hal
