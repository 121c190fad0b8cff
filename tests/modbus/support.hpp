// Helpers shared by the Modbus tests: bounded waits, a raw TCP client for
// hostile traffic, and a Poller config aimed at a local simulator.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "knoblab/modbus/poller.hpp"

namespace knoblab::modbus::test {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

// Polls pred every millisecond until it holds or timeout passes; returns the
// time it took, or nullopt on timeout.
std::optional<std::chrono::milliseconds> wait_for(const std::function<bool()>& pred,
                                                  std::chrono::milliseconds timeout);

bool has(std::uint32_t word, std::uint32_t bits);

// A Poller config for a simulator on 127.0.0.1:port with default unit ids.
PollerConfig local_config(std::uint16_t port);

// A plain TCP socket to 127.0.0.1:port, for bytes no Modbus library would send.
class RawClient {
 public:
  explicit RawClient(std::uint16_t port);
  ~RawClient();
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;

  bool connected() const { return fd_ != -1; }
  bool send(const std::vector<std::uint8_t>& bytes);
  // One Modbus TCP answer (MBAP + PDU); nullopt on timeout or close.
  std::optional<std::vector<std::uint8_t>> receive_frame(std::chrono::milliseconds timeout);
  // True if the server closed the connection within timeout.
  bool closed_by_peer(std::chrono::milliseconds timeout);

 private:
  bool read_exact(std::uint8_t* out, std::size_t n, Clock::time_point deadline);
  int fd_ = -1;
};

// MBAP frame: transaction id 1, protocol 0, the given unit and PDU.
std::vector<std::uint8_t> frame(std::uint8_t unit, const std::vector<std::uint8_t>& pdu);

// A read-input-registers PDU.
std::vector<std::uint8_t> read_inputs_pdu(std::uint16_t addr, std::uint16_t count);

}  // namespace knoblab::modbus::test
