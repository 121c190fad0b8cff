#include "knoblab/hal/gpiod_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "knoblab/hal/config_error.hpp"
#include "test_util.hpp"

namespace knoblab::hal {
namespace {

using test::error_of;
using ::testing::HasSubstr;

nlohmann::json good() {
  return nlohmann::json::parse(R"({"backend": "gpiod", "chip": "/dev/gpiochip0",
    "lines": {"amp_enable": "AMP_EN", "estop": "ESTOP_N", "capture_button": "FOOTSW", "status_led": "LED_STATUS"}})");
}

TEST(GpiodConfig, ParsesNamesWithRoleDefaults) {
  const GpiodLinesConfig c = parse_gpiod_config(good());
  EXPECT_EQ(c.chip, "/dev/gpiochip0");
  EXPECT_EQ(c.amp_enable.name, "AMP_EN");
  EXPECT_EQ(c.estop.name, "ESTOP_N");
  EXPECT_EQ(c.capture_button.name, "FOOTSW");
  EXPECT_EQ(c.status_led.name, "LED_STATUS");
  EXPECT_EQ(c.consumer, "hapticd");
  EXPECT_EQ(c.device_dir, "/dev");
}

TEST(GpiodConfig, EstopDefaultsFailSafeActiveLowPulledDown) {
  const GpiodLinesConfig c = parse_gpiod_config(good());
  EXPECT_TRUE(c.estop.active_low);
  EXPECT_EQ(c.estop.bias, Bias::PullDown);  // open circuit → low → asserted
  EXPECT_TRUE(c.capture_button.active_low);
  EXPECT_EQ(c.capture_button.bias, Bias::PullUp);
  EXPECT_GT(c.capture_button.debounce_us, 0u);
  EXPECT_FALSE(c.amp_enable.active_low);
  EXPECT_FALSE(c.status_led.active_low);
}

TEST(GpiodConfig, ALineObjectOverridesItsDefaults) {
  nlohmann::json j = good();
  j["chip"] = "auto";
  j["lines"]["estop"] = {{"name", "ESTOP"}, {"active_low", false}, {"bias", "pull-up"}, {"debounce_us", 100}};
  const GpiodLinesConfig c = parse_gpiod_config(j);
  EXPECT_EQ(c.chip, "auto");
  EXPECT_EQ(c.estop.name, "ESTOP");
  EXPECT_FALSE(c.estop.active_low);
  EXPECT_EQ(c.estop.bias, Bias::PullUp);
  EXPECT_EQ(c.estop.debounce_us, 100u);
}

TEST(GpiodConfig, MissingKeysAreNamed) {
  nlohmann::json j = good();
  j.erase("chip");
  EXPECT_EQ(error_of<ConfigError>([&] { parse_gpiod_config(j); }), "lines.chip: required key is missing");
  j = good();
  j.erase("lines");
  EXPECT_EQ(error_of<ConfigError>([&] { parse_gpiod_config(j); }), "lines.lines: required key is missing");
  j = good();
  j["lines"].erase("estop");
  EXPECT_EQ(error_of<ConfigError>([&] { parse_gpiod_config(j, "hapticd.lines"); }),
            "hapticd.lines.lines.estop: required key is missing");
  j = good();
  j["lines"]["status_led"] = {{"active_low", true}};
  EXPECT_EQ(error_of<ConfigError>([&] { parse_gpiod_config(j); }),
            "lines.lines.status_led.name: required key is missing");
}

TEST(GpiodConfig, BadValuesAreNamed) {
  nlohmann::json j = good();
  j["lines"]["estop"] = 7;
  EXPECT_THAT(error_of<ConfigError>([&] { parse_gpiod_config(j); }),
              HasSubstr("lines.lines.estop: expected an object, got 7"));
  j = good();
  j["lines"]["estop"] = {{"name", "ESTOP_N"}, {"bias", "pullup"}};
  EXPECT_THAT(error_of<ConfigError>([&] { parse_gpiod_config(j); }),
              HasSubstr("lines.lines.estop.bias: unknown bias \"pullup\""));
  j = good();
  j["lines"]["capture_button"] = "";
  EXPECT_THAT(error_of<ConfigError>([&] { parse_gpiod_config(j); }), HasSubstr("lines.lines.capture_button"));
}

TEST(GpiodConfig, TyposAndDuplicatesAreRejected) {
  nlohmann::json j = good();
  j["lines"]["estp"] = "X";
  EXPECT_THAT(error_of<ConfigError>([&] { parse_gpiod_config(j); }), HasSubstr("lines.lines.estp: unknown key"));
  j = good();
  j["lines"]["status_led"] = "AMP_EN";
  EXPECT_THAT(error_of<ConfigError>([&] { parse_gpiod_config(j); }),
              HasSubstr("amp_enable and status_led both name line \"AMP_EN\""));
}

}  // namespace
}  // namespace knoblab::hal
