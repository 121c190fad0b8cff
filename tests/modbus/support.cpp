#include "support.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

namespace knoblab::modbus::test {

std::optional<std::chrono::milliseconds> wait_for(const std::function<bool()>& pred,
                                                  std::chrono::milliseconds timeout) {
  const auto start = Clock::now();
  while (Clock::now() - start <= timeout) {
    if (pred()) return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start);
    std::this_thread::sleep_for(1ms);
  }
  return std::nullopt;
}

bool has(std::uint32_t word, std::uint32_t bits) { return (word & bits) == bits; }

PollerConfig local_config(std::uint16_t port) {
  PollerConfig c;
  c.amplifier.port = port;
  c.biometrics.port = port;
  c.backoff_max = 200ms;  // quick recovery keeps the suite short
  return c;
}

RawClient::RawClient(std::uint16_t port) {
  fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd_ != -1 && connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

RawClient::~RawClient() {
  if (fd_ != -1) ::close(fd_);
}

bool RawClient::send(const std::vector<std::uint8_t>& bytes) {
  return fd_ != -1 && ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size());
}

bool RawClient::read_exact(std::uint8_t* out, std::size_t n, Clock::time_point deadline) {
  std::size_t got = 0;
  while (got < n) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
    const ssize_t r = recv(fd_, out + got, n - got, 0);
    if (r <= 0) return false;
    got += static_cast<std::size_t>(r);
  }
  return true;
}

std::optional<std::vector<std::uint8_t>> RawClient::receive_frame(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  std::vector<std::uint8_t> out(6);
  if (!read_exact(out.data(), 6, deadline)) return std::nullopt;
  const std::size_t length = (std::size_t{out[4]} << 8) | out[5];
  if (length < 2 || length > 254) return std::nullopt;
  out.resize(6 + length);
  if (!read_exact(out.data() + 6, length, deadline)) return std::nullopt;
  return out;
}

bool RawClient::closed_by_peer(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  std::uint8_t sink[256];
  while (Clock::now() < deadline) {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 10) <= 0) continue;
    const ssize_t r = recv(fd_, sink, sizeof sink, 0);
    if (r <= 0) return true;  // EOF or reset
  }
  return false;
}

std::vector<std::uint8_t> frame(std::uint8_t unit, const std::vector<std::uint8_t>& pdu) {
  const auto length = static_cast<std::uint16_t>(pdu.size() + 1);
  std::vector<std::uint8_t> f{0x00, 0x01, 0x00, 0x00, static_cast<std::uint8_t>(length >> 8),
                              static_cast<std::uint8_t>(length & 0xFF), unit};
  f.insert(f.end(), pdu.begin(), pdu.end());
  return f;
}

std::vector<std::uint8_t> read_inputs_pdu(std::uint16_t addr, std::uint16_t count) {
  return {0x04, static_cast<std::uint8_t>(addr >> 8), static_cast<std::uint8_t>(addr & 0xFF),
          static_cast<std::uint8_t>(count >> 8), static_cast<std::uint8_t>(count & 0xFF)};
}

}  // namespace knoblab::modbus::test
