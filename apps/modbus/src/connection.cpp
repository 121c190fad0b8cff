#include "knoblab/modbus/connection.hpp"

#include <modbus.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

namespace knoblab::modbus {

struct Connection::Context {
  modbus_t* ctx = nullptr;
  ~Context() {
    if (ctx != nullptr) {
      modbus_close(ctx);
      modbus_free(ctx);
    }
  }
};

namespace {

char parity_char(Parity p) {
  switch (p) {
    case Parity::even: return 'E';
    case Parity::odd: return 'O';
    case Parity::none: break;
  }
  return 'N';
}

void set_timeouts(modbus_t* ctx, std::chrono::milliseconds timeout) {
  const auto ms = static_cast<std::uint32_t>(timeout.count());
  const std::uint32_t sec = ms / 1000;
  const std::uint32_t usec = (ms % 1000) * 1000;
  modbus_set_response_timeout(ctx, sec, usec);
  // libmodbus' default byte timeout is 500 ms: a device that stops halfway
  // through an answer would block the poller that long. Bound it the same.
  modbus_set_byte_timeout(ctx, sec, usec);
}

IoResult classify(int err, const std::string& what, Transport kind) {
  IoResult r;
  r.code = err;
  if (err >= EMBXILFUN && err <= EMBXGTAR) {
    r.kind = IoResult::Kind::exception;
    r.code = err - MODBUS_ENOBASE;
  } else if (err == ETIMEDOUT) {
    r.kind = IoResult::Kind::timeout;
  } else if (err == EMBBADCRC || err == EMBBADDATA || err == EMBBADEXC || err == EMBUNKEXC ||
             err == EMBMDATA || err == EMBBADSLAVE) {
    r.kind = IoResult::Kind::bad_response;
  } else {
    r.kind = IoResult::Kind::io;
  }
  r.message = what + ": " + modbus_strerror(err);
  r.reconnect = r.kind != IoResult::Kind::exception &&
                (kind == Transport::tcp || r.kind == IoResult::Kind::io);
  return r;
}

}  // namespace

// The one place that knows Connection's private parts besides Connection.
struct ConnectionFactory {
  static ConnectionResult create(const ModbusEndpoint& e) {
    if (auto problem = validate(e)) return {nullptr, describe(e) + ": " + *problem};
    auto ctx = std::make_unique<Connection::Context>();
    errno = 0;
    if (e.kind == Transport::tcp) {
      // The _pi variant resolves host names and IPv6, not only dotted quads.
      ctx->ctx = modbus_new_tcp_pi(e.host.c_str(), std::to_string(e.port).c_str());
    } else {
      // Only stores the settings: the port is opened (and may fail) in connect().
      ctx->ctx = modbus_new_rtu(e.device.c_str(), static_cast<int>(e.baud), parity_char(e.parity),
                                e.data_bits, e.stop_bits);
    }
    if (ctx->ctx == nullptr) {
      const int err = errno;
      return {nullptr, describe(e) + ": cannot create a libmodbus context: " +
                           (err != 0 ? std::string(std::strerror(err)) : "invalid settings")};
    }
    set_timeouts(ctx->ctx, e.response_timeout);
    return {std::unique_ptr<Connection>(new Connection(e, std::move(ctx))), {}};
  }
};

ConnectionResult make_connection(const ModbusEndpoint& e) { return ConnectionFactory::create(e); }

Connection::Connection(ModbusEndpoint endpoint, std::unique_ptr<Context> ctx)
    : endpoint_(std::move(endpoint)), ctx_(std::move(ctx)) {}

Connection::~Connection() = default;

IoResult Connection::connect() {
  if (open_) return {};
  if (modbus_connect(ctx_->ctx) == -1) {
    const std::string where = endpoint_.kind == Transport::tcp
                                  ? "connect " + describe(endpoint_)
                                  : "open " + endpoint_.device;
    IoResult r = classify(errno, where, endpoint_.kind);
    r.kind = IoResult::Kind::io;  // a failed open is always a link problem
    r.reconnect = true;
    modbus_close(ctx_->ctx);
    return r;
  }
  open_ = true;
  return {};
}

void Connection::close() {
  if (!open_) return;
  modbus_close(ctx_->ctx);
  open_ = false;
}

IoResult Connection::begin(int unit) {
  if (!open_) return {IoResult::Kind::not_connected, 0, describe(endpoint_) + ": not connected", true};
  if (modbus_set_slave(ctx_->ctx, unit) == -1) {
    return {IoResult::Kind::bad_response, errno, "invalid unit id " + std::to_string(unit), false};
  }
  return {};
}

IoResult Connection::finish(int rc, int expected, const char* what) {
  if (rc == expected) return {};
  const std::string where = std::string(what) + " unit " + std::to_string(modbus_get_slave(ctx_->ctx));
  IoResult r = rc == -1 ? classify(errno, where, endpoint_.kind)
                        : IoResult{IoResult::Kind::bad_response, 0, where + ": short answer",
                                   endpoint_.kind == Transport::tcp};
  // On a serial line the rest of a late answer would corrupt the next one.
  if (endpoint_.kind == Transport::rtu && !r.reconnect) modbus_flush(ctx_->ctx);
  return r;
}

IoResult Connection::read_input_registers(int unit, std::uint16_t addr,
                                          std::span<std::uint16_t> out) {
  if (IoResult r = begin(unit); !r.ok()) return r;
  const int n = static_cast<int>(out.size());
  return finish(modbus_read_input_registers(ctx_->ctx, addr, n, out.data()), n, "read input registers");
}

IoResult Connection::read_holding_registers(int unit, std::uint16_t addr,
                                            std::span<std::uint16_t> out) {
  if (IoResult r = begin(unit); !r.ok()) return r;
  const int n = static_cast<int>(out.size());
  return finish(modbus_read_registers(ctx_->ctx, addr, n, out.data()), n, "read holding registers");
}

IoResult Connection::write_register(int unit, std::uint16_t addr, std::uint16_t value) {
  if (IoResult r = begin(unit); !r.ok()) return r;
  return finish(modbus_write_register(ctx_->ctx, addr, value), 1, "write register");
}

IoResult Connection::write_registers(int unit, std::uint16_t addr,
                                     std::span<const std::uint16_t> values) {
  if (IoResult r = begin(unit); !r.ok()) return r;
  const int n = static_cast<int>(values.size());
  return finish(modbus_write_registers(ctx_->ctx, addr, n, values.data()), n, "write registers");
}

}  // namespace knoblab::modbus
