// The simulator's own request framing (mbap.hpp): what reaches modbus_reply()
// is always one whole, well-formed request.
#include <gtest/gtest.h>

#include <vector>

#include "knoblab/modbus/mbap.hpp"

namespace knoblab::modbus::mbap {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Framing, HeaderNeedsSixBytesThenTheWholeFrame) {
  const Bytes f{0, 1, 0, 0, 0, 6, 1, 4, 0, 0, 0, 9};
  std::size_t length = 0;
  EXPECT_EQ(check_header(std::span(f).first(5), length), Header::incomplete);
  EXPECT_EQ(check_header(std::span(f).first(8), length), Header::incomplete);
  EXPECT_EQ(length, 12u);
  EXPECT_EQ(check_header(f, length), Header::complete);
}

TEST(Framing, NonModbusHeadersAreBad) {
  std::size_t length = 0;
  const Bytes http{'G', 'E', 'T', ' ', '/', ' ', 'H'};
  EXPECT_EQ(check_header(http, length), Header::bad);
  EXPECT_EQ(check_header(Bytes{0, 1, 0, 0, 0xFF, 0xFF, 1}, length), Header::bad);  // oversized
  EXPECT_EQ(check_header(Bytes{0, 1, 0, 0, 0, 255, 1}, length), Header::bad);      // 6 + 255 > 260
  EXPECT_EQ(check_header(Bytes{0, 1, 0, 0, 0, 1, 1}, length), Header::bad);        // no function code
  EXPECT_EQ(check_header(Bytes{0, 1, 0, 0, 0, 254, 1}, length), Header::incomplete);  // largest legal
}

TEST(Framing, PduLengthsAndCountsAreChecked) {
  EXPECT_EQ(check_pdu(Bytes{0x04, 0, 0, 0, 9}), Pdu::ok);
  EXPECT_EQ(check_pdu(Bytes{0x04, 0, 0, 0, 9, 0}), Pdu::bad_length);
  EXPECT_EQ(check_pdu(Bytes{0x04, 0, 0, 0, 0}), Pdu::bad_quantity);
  EXPECT_EQ(check_pdu(Bytes{0x03, 0, 0, 0, 126}), Pdu::bad_quantity);
  EXPECT_EQ(check_pdu(Bytes{0x06, 0, 1, 0x12, 0x34}), Pdu::ok);
  EXPECT_EQ(check_pdu(Bytes{0x10, 0, 0, 0, 2, 4, 1, 2, 3, 4}), Pdu::ok);
  EXPECT_EQ(check_pdu(Bytes{0x10, 0, 0, 0, 2, 4, 1, 2, 3}), Pdu::bad_length);     // byte count lies
  EXPECT_EQ(check_pdu(Bytes{0x10, 0, 0, 0, 3, 4, 1, 2, 3, 4}), Pdu::bad_quantity);// count != bytes/2
  EXPECT_EQ(check_pdu(Bytes{0x0F, 0, 0, 0, 9, 2, 0xFF, 1}), Pdu::ok);
  EXPECT_EQ(check_pdu(Bytes{0x17, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 5}), Pdu::ok);
  EXPECT_EQ(check_pdu(Bytes{0x11}), Pdu::ok);
  EXPECT_EQ(check_pdu(Bytes{0x07}), Pdu::unsupported_function);  // libmodbus would stall on it
  EXPECT_EQ(check_pdu(Bytes{0x2B, 0x0E, 1, 0}), Pdu::unsupported_function);
  EXPECT_EQ(check_pdu(Bytes{0x84, 0x02}), Pdu::unsupported_function);
  EXPECT_EQ(check_pdu(Bytes{}), Pdu::bad_length);
}

}  // namespace
}  // namespace knoblab::modbus::mbap
