#include "knoblab/hal/comedi_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "knoblab/hal/config_error.hpp"
#include "test_util.hpp"

namespace knoblab::hal {
namespace {

using test::error_of;
using ::testing::HasSubstr;

nlohmann::json full() {
  return nlohmann::json::parse(R"({
    "backend": "comedi", "device": "/dev/comedi0",
    "torque": {"subdevice": 0, "channel": 0, "range_V": [-1.25, 1.25], "aref": "diff"},
    "accel":  {"channel": 1, "range": 1, "gain": 2.0, "offset_V": -0.05},
    "motor":  {"subdevice": 1, "channel": 0, "range_V": [-10, 10], "gain": -1},
    "encoder": {"device": "/dev/comedi1", "subdevice": 0, "channel": 2, "reset_on_open": true, "sign": -1}})");
}

nlohmann::json minimal() {
  return nlohmann::json::parse(R"({"device": "/dev/comedi0", "torque": {"channel": 0},
    "accel": {"channel": 1}, "motor": {"channel": 0}, "encoder": {"channel": 0}})");
}

std::string error_for(const nlohmann::json& j) {
  return error_of<ConfigError>([&] { parse_comedi_config(j); });
}

TEST(ComediConfig, ParsesEveryField) {
  const ComediDaqConfig c = parse_comedi_config(full());
  EXPECT_EQ(c.device, "/dev/comedi0");
  EXPECT_EQ(c.torque.subdevice, 0u);
  EXPECT_EQ(c.torque.channel, 0u);
  ASSERT_TRUE(c.torque.range_V.has_value());
  EXPECT_DOUBLE_EQ(c.torque.range_V->min_V, -1.25);
  EXPECT_DOUBLE_EQ(c.torque.range_V->max_V, 1.25);
  EXPECT_FALSE(c.torque.range.has_value());
  EXPECT_EQ(c.torque.aref, Aref::Diff);
  EXPECT_FALSE(c.accel.subdevice.has_value());
  EXPECT_EQ(c.accel.range, 1u);
  EXPECT_DOUBLE_EQ(c.accel.gain, 2.0);
  EXPECT_DOUBLE_EQ(c.accel.offset_V, -0.05);
  EXPECT_DOUBLE_EQ(c.motor.gain, -1.0);
  EXPECT_EQ(c.encoder.device, "/dev/comedi1");
  EXPECT_EQ(c.encoder.channel, 2u);
  EXPECT_TRUE(c.encoder.reset_on_open);
  EXPECT_EQ(c.encoder.sign, -1);
}

TEST(ComediConfig, MinimalConfigTakesDefaults) {
  const ComediDaqConfig c = parse_comedi_config(minimal());
  EXPECT_FALSE(c.torque.subdevice.has_value());
  EXPECT_FALSE(c.torque.range.has_value());
  EXPECT_FALSE(c.torque.range_V.has_value());
  EXPECT_EQ(c.torque.aref, Aref::Ground);
  EXPECT_DOUBLE_EQ(c.torque.gain, 1.0);
  EXPECT_EQ(c.encoder.device, "");
  EXPECT_FALSE(c.encoder.reset_on_open);
  EXPECT_EQ(c.encoder.sign, 1);
}

TEST(ComediConfig, EachMissingKeyIsNamed) {
  for (const char* key : {"device", "torque", "accel", "motor", "encoder"}) {
    nlohmann::json j = minimal();
    j.erase(key);
    EXPECT_EQ(error_for(j), std::string("daq.") + key + ": required key is missing");
  }
  for (const char* key : {"torque", "accel", "motor", "encoder"}) {
    nlohmann::json j = minimal();
    j[key].erase("channel");
    EXPECT_EQ(error_for(j), std::string("daq.") + key + ".channel: required key is missing");
  }
}

TEST(ComediConfig, WrongTypesAreNamed) {
  nlohmann::json j = minimal();
  j["torque"]["channel"] = -1;
  EXPECT_EQ(error_for(j), "daq.torque.channel: expected a non-negative integer, got -1");
  j = minimal();
  j["accel"]["channel"] = 1.5;
  EXPECT_EQ(error_for(j), "daq.accel.channel: expected a non-negative integer, got 1.5");
  j = minimal();
  j["device"] = 0;
  EXPECT_EQ(error_for(j), "daq.device: expected a string, got 0");
  j = minimal();
  j["motor"] = "ao0";
  EXPECT_EQ(error_for(j), "daq.motor: expected an object, got \"ao0\"");
  j = minimal();
  j["encoder"]["reset_on_open"] = "yes";
  EXPECT_EQ(error_for(j), "daq.encoder.reset_on_open: expected true or false, got \"yes\"");
}

TEST(ComediConfig, BadRangesAreRejected) {
  nlohmann::json j = minimal();
  j["torque"]["range_V"] = {1.25};
  EXPECT_THAT(error_for(j), HasSubstr("daq.torque.range_V: expected [min_V, max_V]"));
  j["torque"]["range_V"] = {1.25, -1.25};
  EXPECT_THAT(error_for(j), HasSubstr("daq.torque.range_V: min must be below max"));
  j["torque"]["range_V"] = {"-1.25", 1.25};
  EXPECT_THAT(error_for(j), HasSubstr("daq.torque.range_V[0]: expected a number"));
  j["torque"]["range_V"] = {-1.25, 1.25};
  j["torque"]["range"] = 3;
  EXPECT_THAT(error_for(j), HasSubstr("either \"range\" (index) or \"range_V\", not both"));
}

TEST(ComediConfig, BadValuesAreRejected) {
  nlohmann::json j = minimal();
  j["torque"]["aref"] = "differential";
  EXPECT_THAT(error_for(j), HasSubstr("daq.torque.aref: unknown reference \"differential\""));
  j = minimal();
  j["encoder"]["sign"] = 2;
  EXPECT_EQ(error_for(j), "daq.encoder.sign: must be 1 or -1");
  j = minimal();
  j["motor"]["gain"] = 0;
  EXPECT_EQ(error_for(j), "daq.motor.gain: must not be 0");
  j = minimal();
  j["device"] = "";
  EXPECT_THAT(error_for(j), HasSubstr("daq.device: must be a device path"));
}

TEST(ComediConfig, UnknownKeysAreTyposNotDefaults) {
  nlohmann::json j = minimal();
  j["torque"]["chanel"] = 3;
  EXPECT_THAT(error_for(j), HasSubstr("daq.torque.chanel: unknown key (known here: aref, channel, gain"));
  j = minimal();
  j["motor"]["offset_V"] = 0.1;  // inputs only
  EXPECT_THAT(error_for(j), HasSubstr("daq.motor.offset_V: unknown key"));
  j = minimal();
  j["rate_hz"] = 10000;
  EXPECT_THAT(error_for(j), HasSubstr("daq.rate_hz: unknown key"));
}

}  // namespace
}  // namespace knoblab::hal
