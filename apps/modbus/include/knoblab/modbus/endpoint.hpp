// Where a Modbus device is and how to reach it. TCP and RTU are both just
// configuration: one Connection type serves either (connection.hpp).
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace knoblab::modbus {

enum class Transport { tcp, rtu };
enum class Parity { none, even, odd };

struct ModbusEndpoint {
  Transport kind = Transport::tcp;
  // TCP
  std::string host = "127.0.0.1";
  std::uint16_t port = 502;
  // RTU (serial)
  std::string device;  // e.g. /dev/ttyUSB0
  std::uint32_t baud = 115200;
  Parity parity = Parity::none;
  int data_bits = 8;  // 5..8
  int stop_bits = 1;  // 1 or 2
  // Both
  int unit_id = 1;  // 1..247 (0 is broadcast)
  // Per request. Keep it short: it bounds how long a hung device can block
  // the poller and how long Poller::stop() can take.
  std::chrono::milliseconds response_timeout{20};
};

// A problem with the configuration, or nullopt if it is usable.
std::optional<std::string> validate(const ModbusEndpoint& e);

// "tcp 127.0.0.1:1502 unit 1" / "rtu /dev/ttyUSB0 115200 8E1 unit 2".
std::string describe(const ModbusEndpoint& e);

// Endpoints that share a transport share one Connection: an RTU bus is one
// serial port whatever the unit id. TCP endpoints each get their own socket
// (independent failures), so their key includes the unit id.
std::string transport_key(const ModbusEndpoint& e);

}  // namespace knoblab::modbus
