#include "knoblab/modbus/endpoint.hpp"

#include <string>

namespace knoblab::modbus {
namespace {

char parity_letter(Parity p) {
  switch (p) {
    case Parity::even: return 'E';
    case Parity::odd: return 'O';
    case Parity::none: break;
  }
  return 'N';
}

}  // namespace

std::optional<std::string> validate(const ModbusEndpoint& e) {
  if (e.unit_id < 1 || e.unit_id > 247) return "unit id must be 1..247, got " + std::to_string(e.unit_id);
  if (e.response_timeout.count() <= 0) return "response timeout must be positive";
  if (e.kind == Transport::tcp) {
    if (e.host.empty()) return "tcp endpoint without a host";
    if (e.port == 0) return "tcp endpoint without a port";
    return std::nullopt;
  }
  if (e.device.empty()) return "rtu endpoint without a serial device";
  if (e.baud == 0) return "rtu baud rate must be positive";
  if (e.data_bits < 5 || e.data_bits > 8) return "rtu data bits must be 5..8";
  if (e.stop_bits != 1 && e.stop_bits != 2) return "rtu stop bits must be 1 or 2";
  return std::nullopt;
}

std::string describe(const ModbusEndpoint& e) {
  const std::string unit = " unit " + std::to_string(e.unit_id);
  if (e.kind == Transport::tcp) return "tcp " + e.host + ":" + std::to_string(e.port) + unit;
  return "rtu " + e.device + " " + std::to_string(e.baud) + " " + std::to_string(e.data_bits) +
         parity_letter(e.parity) + std::to_string(e.stop_bits) + unit;
}

std::string transport_key(const ModbusEndpoint& e) {
  if (e.kind == Transport::rtu) return "rtu " + e.device;
  return describe(e);
}

}  // namespace knoblab::modbus
