#include "knoblab/modbus/mbap.hpp"

namespace knoblab::modbus::mbap {
namespace {

std::size_t u16_at(std::span<const std::uint8_t> b, std::size_t i) {
  return (std::size_t{b[i]} << 8) | b[i + 1];
}

bool in(std::size_t v, std::size_t lo, std::size_t hi) { return v >= lo && v <= hi; }

// Function codes: the ones libmodbus' modbus_reply() implements, minus 0x07
// (it answers that by sleeping and flushing, which would stall the server).
enum Fc : std::uint8_t {
  kReadCoils = 0x01,
  kReadDiscreteInputs = 0x02,
  kReadHolding = 0x03,
  kReadInput = 0x04,
  kWriteCoil = 0x05,
  kWriteRegister = 0x06,
  kWriteCoils = 0x0F,
  kWriteRegisters = 0x10,
  kReportServerId = 0x11,
  kMaskWrite = 0x16,
  kWriteAndRead = 0x17,
};

}  // namespace

Header check_header(std::span<const std::uint8_t> buffer, std::size_t& frame_length) {
  if (buffer.size() < 6) return Header::incomplete;
  const std::size_t protocol = u16_at(buffer, 2);
  const std::size_t length = u16_at(buffer, 4);  // unit id + PDU
  if (protocol != 0 || !in(length, 2, kMaxAduLength - 6)) return Header::bad;
  frame_length = 6 + length;
  return buffer.size() >= frame_length ? Header::complete : Header::incomplete;
}

Pdu check_pdu(std::span<const std::uint8_t> pdu) {
  if (pdu.empty()) return Pdu::bad_length;
  const std::size_t n = pdu.size();
  switch (pdu[0]) {
    case kReadCoils:
    case kReadDiscreteInputs:
      if (n != 5) return Pdu::bad_length;
      return in(u16_at(pdu, 3), 1, 2000) ? Pdu::ok : Pdu::bad_quantity;
    case kReadHolding:
    case kReadInput:
      if (n != 5) return Pdu::bad_length;
      return in(u16_at(pdu, 3), 1, 125) ? Pdu::ok : Pdu::bad_quantity;
    case kWriteCoil:
    case kWriteRegister:
      return n == 5 ? Pdu::ok : Pdu::bad_length;
    case kWriteCoils: {
      if (n < 6 || n != 6 + std::size_t{pdu[5]}) return Pdu::bad_length;
      const std::size_t count = u16_at(pdu, 3);
      return in(count, 1, 1968) && pdu[5] == (count + 7) / 8 ? Pdu::ok : Pdu::bad_quantity;
    }
    case kWriteRegisters: {
      if (n < 6 || n != 6 + std::size_t{pdu[5]}) return Pdu::bad_length;
      const std::size_t count = u16_at(pdu, 3);
      return in(count, 1, 123) && pdu[5] == 2 * count ? Pdu::ok : Pdu::bad_quantity;
    }
    case kReportServerId:
      return n == 1 ? Pdu::ok : Pdu::bad_length;
    case kMaskWrite:
      return n == 7 ? Pdu::ok : Pdu::bad_length;
    case kWriteAndRead: {
      if (n < 10 || n != 10 + std::size_t{pdu[9]}) return Pdu::bad_length;
      const std::size_t reads = u16_at(pdu, 3);
      const std::size_t writes = u16_at(pdu, 7);
      return in(reads, 1, 125) && in(writes, 1, 121) && pdu[9] == 2 * writes ? Pdu::ok
                                                                                : Pdu::bad_quantity;
    }
    default:
      return Pdu::unsupported_function;
  }
}

}  // namespace knoblab::modbus::mbap
