// One Modbus client transport (a TCP socket or a serial port), whatever the
// endpoint's kind: make_connection() is the only place TCP and RTU differ.
// Not thread-safe; the poller thread owns its connections.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "knoblab/modbus/endpoint.hpp"

namespace knoblab::modbus {

struct IoResult {
  enum class Kind {
    ok,
    exception,      // the device answered with a Modbus exception (code)
    timeout,        // no (complete) answer within the response timeout
    io,             // socket/serial error, connection closed (code = errno)
    bad_response,   // answer did not match the request
    not_connected,
  };
  Kind kind = Kind::ok;
  int code = 0;  // exception code or errno
  std::string message;
  // The link itself is suspect: close it and reconnect. Never for a Modbus
  // exception (a well-formed answer). On TCP any other error, since a late
  // answer would desynchronise the stream; on RTU only a port error, since
  // one silent unit must not take the shared bus down for the others.
  bool reconnect = false;

  bool ok() const { return kind == Kind::ok; }
};

class Connection {
 public:
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  IoResult connect();  // open the socket / serial port
  void close();
  bool is_open() const { return open_; }
  const ModbusEndpoint& endpoint() const { return endpoint_; }

  IoResult read_input_registers(int unit, std::uint16_t addr, std::span<std::uint16_t> out);
  IoResult read_holding_registers(int unit, std::uint16_t addr, std::span<std::uint16_t> out);
  IoResult write_register(int unit, std::uint16_t addr, std::uint16_t value);
  IoResult write_registers(int unit, std::uint16_t addr, std::span<const std::uint16_t> values);

 private:
  struct Context;  // owns the libmodbus context; keeps <modbus.h> out of this header
  Connection(ModbusEndpoint endpoint, std::unique_ptr<Context> ctx);
  IoResult begin(int unit);
  IoResult finish(int rc, int expected, const char* what);
  friend struct ConnectionFactory;

  ModbusEndpoint endpoint_;
  std::unique_ptr<Context> ctx_;
  bool open_ = false;
};

struct ConnectionResult {
  std::unique_ptr<Connection> connection;  // null on error
  std::string error;
};

// Builds the libmodbus context for the endpoint (modbus_new_tcp_pi or
// modbus_new_rtu) with its timeouts; does not open it yet.
ConnectionResult make_connection(const ModbusEndpoint& endpoint);

}  // namespace knoblab::modbus
