// PollerConfig's rules, checked before any thread starts: a configuration in
// which one unanswered request would raise a watchdog is refused, naming the
// setting and the figures that clash. Nothing here connects anywhere.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "knoblab/modbus/poller.hpp"

namespace knoblab::modbus {
namespace {

using std::chrono::milliseconds;

std::string ms(Millis d) { return std::to_string(d.count()) + " ms"; }

// What the Poller's constructor says about c ("" if it accepts it).
std::string refusal(const PollerConfig& c) {
  try {
    Poller p(c);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

ModbusEndpoint on_bus(const std::string& device, int unit) {
  ModbusEndpoint e;
  e.kind = Transport::rtu;
  e.device = device;
  e.unit_id = unit;
  return e;
}

TEST(PollerConfig, TheDefaultsPass) {
  EXPECT_FALSE(validate(PollerConfig{}));
  EXPECT_EQ(refusal(PollerConfig{}), "");
}

TEST(PollerConfig, AnAmplifierResponseTimeoutThatOneUnansweredRequestWouldTurnIntoCommsLostIsRefused) {
  PollerConfig c;
  c.amplifier.response_timeout = c.comms_timeout - c.amplifier_period;  // the read after it lands just late
  const auto problem = validate(c);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->setting, "amplifier.response_timeout");
  const std::string why = refusal(c);
  EXPECT_NE(why.find("amplifier.response_timeout"), std::string::npos) << why;
  for (const Millis figure : {c.amplifier.response_timeout, c.amplifier_period, c.comms_timeout})
    EXPECT_NE(why.find(ms(figure)), std::string::npos) << ms(figure) << " in: " << why;

  c.amplifier.response_timeout -= milliseconds{1};
  EXPECT_FALSE(validate(c));
  c.comms_timeout -= milliseconds{1};  // the same clash from the watchdog's side
  EXPECT_TRUE(validate(c));
}

TEST(PollerConfig, ABiometricsResponseTimeoutThatCannotKeepUpWithTheBiometricsTimeoutIsRefused) {
  PollerConfig c;
  c.biometrics.response_timeout = c.biometrics_timeout - c.biometrics_period;
  const auto problem = validate(c);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->setting, "biometrics.response_timeout");
  const std::string why = refusal(c);
  for (const Millis figure : {c.biometrics.response_timeout, c.biometrics_period, c.biometrics_timeout})
    EXPECT_NE(why.find(ms(figure)), std::string::npos) << ms(figure) << " in: " << why;

  c.biometrics.response_timeout -= milliseconds{1};
  EXPECT_FALSE(validate(c));
}

TEST(PollerConfig, ADeviceNotPolledIsNotHeldToItsWatchdog) {
  PollerConfig c;
  c.poll_biometrics = false;
  c.biometrics.response_timeout = c.biometrics_timeout * 10;
  EXPECT_FALSE(validate(c));
  c = PollerConfig{};
  c.poll_amplifier = false;
  c.amplifier.response_timeout = c.comms_timeout * 10;
  EXPECT_FALSE(validate(c));
  c.poll_biometrics = false;
  ASSERT_TRUE(validate(c));
  EXPECT_EQ(validate(c)->why, "nothing to poll");
}

TEST(PollerConfig, DevicesOnOneRtuBusMustAgreeOnTheLineAndTheResponseTimeout) {
  PollerConfig c;
  c.amplifier = on_bus("/dev/ttyUSB0", 1);
  c.biometrics = on_bus("/dev/ttyUSB0", 2);
  EXPECT_FALSE(validate(c));
  EXPECT_EQ(refusal(c), "");  // building the connection does not open the port

  PollerConfig other = c;
  other.biometrics.baud = c.amplifier.baud / 2;
  ASSERT_TRUE(validate(other));
  EXPECT_EQ(validate(other)->setting, "biometrics.baud");
  other = c;
  other.biometrics.parity = Parity::even;
  ASSERT_TRUE(validate(other));
  EXPECT_EQ(validate(other)->setting, "biometrics.parity");
  other = c;
  other.biometrics.response_timeout = c.amplifier.response_timeout + milliseconds{5};
  ASSERT_TRUE(validate(other));
  EXPECT_EQ(validate(other)->setting, "biometrics.response_timeout");
  other = c;
  other.biometrics.unit_id = c.amplifier.unit_id;
  ASSERT_TRUE(validate(other));
  EXPECT_EQ(validate(other)->setting, "biometrics.unit_id");

  // Separate buses are separate lines: nothing to agree on.
  other = c;
  other.biometrics.device = "/dev/ttyUSB1";
  other.biometrics.baud = c.amplifier.baud / 2;
  other.biometrics.response_timeout = c.amplifier.response_timeout + milliseconds{5};
  EXPECT_FALSE(validate(other));
}

TEST(PollerConfig, TwoTcpDevicesAtOneAddressAndUnitAreRefused) {
  PollerConfig c;
  c.biometrics.unit_id = c.amplifier.unit_id;  // same host and port by default
  ASSERT_TRUE(validate(c));
  EXPECT_EQ(validate(c)->setting, "biometrics.unit_id");
  c.biometrics.port = static_cast<std::uint16_t>(c.amplifier.port + 1);  // another server
  EXPECT_FALSE(validate(c));
}

TEST(PollerConfig, AnEndpointProblemNamesTheDevice) {
  PollerConfig c;
  c.biometrics.unit_id = 0;
  ASSERT_TRUE(validate(c));
  EXPECT_EQ(validate(c)->setting, "biometrics");
  EXPECT_NE(refusal(c).find("unit id must be 1..247"), std::string::npos) << refusal(c);
}

}  // namespace
}  // namespace knoblab::modbus
