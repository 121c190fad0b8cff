// Server-side framing of Modbus TCP requests, checked before libmodbus sees
// them. The simulator frames requests itself (by the MBAP length field, from
// a per-client buffer) instead of calling modbus_receive(): that call blocks
// until a frame is complete and sizes frames by function code, so one client
// sending a truncated or unknown frame would stall every other client.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace knoblab::modbus::mbap {

// Transaction id (2), protocol id (2), length (2), unit id (1).
inline constexpr std::size_t kHeaderLength = 7;
inline constexpr std::size_t kMaxAduLength = 260;  // 6 + the largest length field, 254

enum class Header {
  incomplete,  // need more bytes
  complete,    // a whole frame of frame_length bytes is buffered
  bad,         // not Modbus TCP: protocol id != 0 or length outside 2..254
};

// Looks at the start of a client's receive buffer. frame_length is set once
// the length field has arrived (incomplete or complete).
Header check_header(std::span<const std::uint8_t> buffer, std::size_t& frame_length);

enum class Pdu {
  ok,
  unsupported_function,  // reply ILLEGAL_FUNCTION
  bad_length,            // length does not fit the function: reply ILLEGAL_DATA_VALUE
  bad_quantity,          // count or byte count out of range: reply ILLEGAL_DATA_VALUE
};

// The PDU (function code + data) of one frame, checked so that libmodbus'
// modbus_reply() only ever sees well-formed requests of the exact length it
// assumes (it trusts the counts inside the request).
Pdu check_pdu(std::span<const std::uint8_t> pdu);

}  // namespace knoblab::modbus::mbap
