// Endpoint configuration and the Connection factory: TCP and RTU are one
// code path; a missing serial device is a clear error, not a crash.
#include <gtest/gtest.h>

#include "knoblab/modbus/connection.hpp"
#include "knoblab/modbus/endpoint.hpp"
#include "knoblab/modbus/poller.hpp"
#include "knoblab/modbus/sim_server.hpp"
#include "support.hpp"

namespace knoblab::modbus {
namespace {

ModbusEndpoint rtu(const std::string& device) {
  ModbusEndpoint e;
  e.kind = Transport::rtu;
  e.device = device;
  e.baud = 57600;
  e.parity = Parity::even;
  e.unit_id = 2;
  return e;
}

TEST(Endpoint, DescribeAndValidate) {
  ModbusEndpoint tcp;
  tcp.port = 1502;
  EXPECT_EQ(describe(tcp), "tcp 127.0.0.1:1502 unit 1");
  EXPECT_FALSE(validate(tcp));
  EXPECT_EQ(describe(rtu("/dev/ttyUSB0")), "rtu /dev/ttyUSB0 57600 8E1 unit 2");
  EXPECT_FALSE(validate(rtu("/dev/ttyUSB0")));

  ModbusEndpoint bad = tcp;
  bad.unit_id = 0;
  EXPECT_TRUE(validate(bad));
  bad = rtu("");
  EXPECT_TRUE(validate(bad));
  bad = rtu("/dev/ttyS0");
  bad.stop_bits = 3;
  EXPECT_TRUE(validate(bad));
}

TEST(Endpoint, RtuUnitsShareOneBusTcpUnitsDoNot) {
  auto a = rtu("/dev/ttyUSB0");
  auto b = a;
  b.unit_id = 1;
  EXPECT_EQ(transport_key(a), transport_key(b));
  ModbusEndpoint t1, t2;
  t2.unit_id = 2;
  EXPECT_NE(transport_key(t1), transport_key(t2));
}

TEST(Endpoint, RtuWithMissingDeviceBuildsAContextAndFailsToOpenClearly) {
  auto made = make_connection(rtu("/dev/knoblab-no-such-tty"));
  ASSERT_TRUE(made.connection) << made.error;
  const IoResult r = made.connection->connect();
  EXPECT_EQ(r.kind, IoResult::Kind::io);
  EXPECT_NE(r.message.find("/dev/knoblab-no-such-tty"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("No such file"), std::string::npos) << r.message;
  EXPECT_FALSE(made.connection->is_open());
  std::uint16_t reg = 0;
  EXPECT_EQ(made.connection->read_input_registers(2, 0, std::span(&reg, 1)).kind,
            IoResult::Kind::not_connected);
}

TEST(Endpoint, InvalidConfigIsAnErrorNotAContext) {
  auto made = make_connection(rtu(""));
  EXPECT_FALSE(made.connection);
  EXPECT_NE(made.error.find("serial device"), std::string::npos) << made.error;
}

TEST(Endpoint, PollerOnAMissingSerialPortKeepsRetryingAndReportsLinksLost) {
  PollerConfig c;
  c.amplifier = rtu("/dev/knoblab-no-such-tty");
  c.amplifier.unit_id = 1;
  c.biometrics = rtu("/dev/knoblab-no-such-tty");  // same bus, one Connection
  Poller poller(c);
  poller.start();
  ASSERT_TRUE(test::wait_for([&] { return poller.stats().connect_failures >= 2; }, std::chrono::seconds(2)));
  EXPECT_TRUE(test::has(poller.status(), status::kAmpCommsLost | status::kBiometricsLost));
  EXPECT_NE(poller.stats().last_error.find("No such file"), std::string::npos);
  poller.stop();
}

TEST(Endpoint, PollerRejectsBadConfig) {
  PollerConfig c;
  c.biometrics_period = std::chrono::milliseconds(40);  // would miss 32 Hz samples
  EXPECT_THROW(Poller{c}, std::invalid_argument);
  c = PollerConfig{};
  c.amplifier.unit_id = 300;
  EXPECT_THROW(Poller{c}, std::invalid_argument);
}

TEST(Endpoint, TcpConnectRefusedIsAnIoError) {
  // Bind a server to get a free port, then stop it: nothing listens there.
  SimServer sim({});
  ASSERT_TRUE(sim.start());
  ModbusEndpoint e;
  e.port = sim.port();
  sim.stop();
  auto made = make_connection(e);
  ASSERT_TRUE(made.connection);
  const IoResult r = made.connection->connect();
  EXPECT_EQ(r.kind, IoResult::Kind::io);
  EXPECT_TRUE(r.reconnect);
  EXPECT_NE(r.message.find("refused"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace knoblab::modbus
