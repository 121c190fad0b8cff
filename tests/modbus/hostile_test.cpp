// Hostile traffic to the simulator's server: it must never crash, never
// stall, and keep serving a well-behaved client throughout.
#include <gtest/gtest.h>

#include <modbus.h>

#include <memory>
#include <random>
#include <vector>

#include "knoblab/modbus/register_map.hpp"
#include "knoblab/modbus/sim_server.hpp"
#include "support.hpp"

namespace knoblab::modbus {
namespace {

using namespace test;
using Bytes = std::vector<std::uint8_t>;

class HostileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SimConfig c;
    c.partial_frame_timeout = 300ms;
    sim_ = std::make_unique<SimServer>(c);
    std::string error;
    ASSERT_TRUE(sim_->start(&error)) << error;
    good_ = modbus_new_tcp("127.0.0.1", sim_->port());
    ASSERT_NE(good_, nullptr);
    modbus_set_response_timeout(good_, 0, 100'000);
    ASSERT_EQ(modbus_connect(good_), 0);
    modbus_set_slave(good_, kDefaultAmplifierUnit);
  }
  void TearDown() override {
    if (good_ != nullptr) {
      modbus_close(good_);
      modbus_free(good_);
    }
    sim_->stop();
  }

  // The good client reads the amplifier block promptly.
  void expect_good_client_served(const char* after) {
    std::uint16_t regs[amp::kInputCount] = {};
    const auto t0 = Clock::now();
    EXPECT_EQ(modbus_read_input_registers(good_, 0, amp::kInputCount, regs), amp::kInputCount)
        << "after " << after << ": " << modbus_strerror(errno);
    EXPECT_LT(Clock::now() - t0, 50ms) << "after " << after;
    EXPECT_EQ(regs[ident::kDeviceType], static_cast<std::uint16_t>(DeviceType::amplifier));
  }

  // Sends one frame on a fresh connection and returns the exception code of
  // the answer (0 for a normal answer, -1 for none).
  int exception_for(const Bytes& bytes) {
    RawClient raw(sim_->port());
    EXPECT_TRUE(raw.send(bytes));
    const auto answer = raw.receive_frame(500ms);
    if (!answer || answer->size() < 9) return -1;
    EXPECT_EQ((*answer)[7] & 0x7F, bytes[7]);  // same function code
    return ((*answer)[7] & 0x80) != 0 ? (*answer)[8] : 0;
  }

  std::unique_ptr<SimServer> sim_;
  modbus_t* good_ = nullptr;
};

TEST_F(HostileTest, GarbageAndBadHeadersCloseThatConnectionOnly) {
  for (const Bytes& junk : {Bytes{'G', 'E', 'T', ' ', '/', ' ', 'H', 'T', 'T', 'P', '/', '1', '.', '1', '\r', '\n'},
                            Bytes{0, 1, 0, 0, 0xFF, 0xFF, 1, 4, 0, 0, 0, 1},  // oversized length field
                            Bytes{0, 1, 0, 0, 0, 0, 1},                        // zero length
                            Bytes{0, 1, 0x12, 0x34, 0, 6, 1, 4, 0, 0, 0, 1}}) {  // protocol id != 0
    RawClient raw(sim_->port());
    ASSERT_TRUE(raw.send(junk));
    EXPECT_TRUE(raw.closed_by_peer(500ms));
    expect_good_client_served("junk");
  }
  EXPECT_EQ(sim_->counters().bad_frames, 4u);
}

TEST_F(HostileTest, IllegalFunctionsAndAddressesGetExceptionsAndTheConnectionStays) {
  EXPECT_EQ(exception_for(frame(1, {0x07})), MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  EXPECT_EQ(exception_for(frame(1, {0x2B, 0x0E, 0x01, 0x00})), MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  EXPECT_EQ(exception_for(frame(1, {0x00})), MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  EXPECT_EQ(exception_for(frame(1, {0x7F, 1, 2, 3})), MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  EXPECT_EQ(exception_for(frame(1, read_inputs_pdu(0xFFF0, 100))), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_for(frame(1, read_inputs_pdu(amp::kInputCount, 1))), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(exception_for(frame(2, {0x06, 0x00, 0x00, 0x00, 0x01})), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);  // read-only box
  EXPECT_EQ(exception_for(frame(1, {0x01, 0, 0, 0, 8})), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);  // no coils
  EXPECT_EQ(exception_for(frame(1, read_inputs_pdu(0, 0))), MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
  EXPECT_EQ(exception_for(frame(1, read_inputs_pdu(0, 126))), MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
  EXPECT_EQ(exception_for(frame(1, {0x10, 0, 0, 0, 2, 3, 0, 1, 0})), MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);  // byte count lies
  EXPECT_EQ(exception_for(frame(1, {0x03, 0, 0, 0, 1, 0xAA, 0xBB})), MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);  // trailing bytes
  EXPECT_EQ(exception_for(frame(99, read_inputs_pdu(0, 1))), MODBUS_EXCEPTION_GATEWAY_TARGET);  // no such unit
  EXPECT_EQ(exception_for(frame(1, read_inputs_pdu(0, amp::kInputCount))), 0);
  expect_good_client_served("illegal requests");

  // Pipelined requests on one connection, exceptions in between, all answered in order.
  RawClient raw(sim_->port());
  Bytes burst = frame(1, {0x07});
  for (const Bytes& f : {frame(2, read_inputs_pdu(0, 2)), frame(1, {0x42})}) burst.insert(burst.end(), f.begin(), f.end());
  ASSERT_TRUE(raw.send(burst));
  for (int expected_fc : {0x87, 0x04, 0xC2}) {
    const auto answer = raw.receive_frame(500ms);
    ASSERT_TRUE(answer);
    EXPECT_EQ((*answer)[7], expected_fc);
  }
}

TEST_F(HostileTest, TruncatedFramesDoNotStallOthersAndAreDroppedAfterATimeout) {
  RawClient stuck(sim_->port());
  const Bytes whole = frame(1, read_inputs_pdu(0, 9));
  ASSERT_TRUE(stuck.send(Bytes(whole.begin(), whole.begin() + 9)));  // header + part of the PDU
  RawClient header_only(sim_->port());
  ASSERT_TRUE(header_only.send(Bytes(whole.begin(), whole.begin() + 3)));
  for (int i = 0; i < 5; ++i) expect_good_client_served("a truncated frame");
  EXPECT_TRUE(stuck.closed_by_peer(1s));        // partial_frame_timeout = 300 ms
  EXPECT_TRUE(header_only.closed_by_peer(1s));
  expect_good_client_served("dropping stuck clients");
}

TEST_F(HostileTest, ConnectionFloodIsCappedAndTheGoodClientKeepsItsSlot) {
  std::vector<std::unique_ptr<RawClient>> flood;
  for (int i = 0; i < 40; ++i) flood.push_back(std::make_unique<RawClient>(sim_->port()));
  int refused = 0;
  for (auto& c : flood) refused += c->closed_by_peer(20ms) ? 1 : 0;
  EXPECT_GE(refused, 40 - 31);  // max_clients 32, one is the good client
  expect_good_client_served("a connection flood");
}

TEST_F(HostileTest, RandomFramesNeverCrashTheServer) {
  std::mt19937 rng(1234);
  std::uniform_int_distribution<int> byte(0, 255);
  const std::uint8_t units[] = {1, 2, 0, 99, 255};  // never the control unit: no self-inflicted faults
  int answered = 0;
  for (int i = 0; i < 200; ++i) {
    RawClient raw(sim_->port());
    Bytes pdu(static_cast<std::size_t>(1 + byte(rng) % 20));
    for (auto& b : pdu) b = static_cast<std::uint8_t>(byte(rng));
    if (i % 3 == 0) pdu[0] = static_cast<std::uint8_t>(1 + byte(rng) % 0x17);  // mostly real function codes
    Bytes f = frame(units[byte(rng) % 5], pdu);
    if (i % 7 == 0) f.resize(static_cast<std::size_t>(byte(rng)) % f.size());  // truncated
    if (i % 11 == 0) f[4] = static_cast<std::uint8_t>(byte(rng));              // lying length
    ASSERT_TRUE(f.empty() || raw.send(f));
    if (raw.receive_frame(20ms)) ++answered;
  }
  EXPECT_GT(answered, 90);
  expect_good_client_served("random frames");
  EXPECT_TRUE(sim_->running());
}

}  // namespace
}  // namespace knoblab::modbus
