#include "connection.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

namespace knoblab::control::detail {

Connection::Connection(UniqueFd fd, ClientId id, std::size_t max_queued_bytes, Clock::time_point accepted,
                       std::optional<pid_t> peer)
    : accepted_at(accepted), peer_pid(peer), fd_(std::move(fd)), id_(id), max_queued_bytes_(max_queued_bytes) {}

std::optional<pid_t> peer_process(int fd) {
  ucred cred{};
  socklen_t len = sizeof cred;
  if (::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) != 0 || len != sizeof cred) return std::nullopt;
  if (cred.pid <= 0) return std::nullopt;  // the peer lives where our pids cannot name it
  return cred.pid;
}

Connection::ReadStatus Connection::read_some() {
  const auto area = decoder_.write_area();
  if (area.empty()) return ReadStatus::would_block;  // decoder holds a whole frame or is oversized
  for (;;) {
    const ssize_t n = ::read(fd_.get(), area.data(), area.size());
    if (n > 0) {
      decoder_.commit(static_cast<std::size_t>(n));
      return ReadStatus::data;
    }
    if (n == 0) return ReadStatus::eof;
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return ReadStatus::would_block;
    return ReadStatus::error;
  }
}

bool Connection::enqueue(Frame frame) {
  if (queued_bytes_ + frame->size() > max_queued_bytes_) return false;
  queued_bytes_ += frame->size();
  queue_.push_back(std::move(frame));
  return true;
}

bool Connection::flush() {
  while (!queue_.empty()) {
    const std::string& f = *queue_.front();
    const ssize_t n = ::send(fd_.get(), f.data() + front_offset_, f.size() - front_offset_,
                             MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return true;
      return false;
    }
    front_offset_ += static_cast<std::size_t>(n);
    if (front_offset_ == f.size()) {
      queued_bytes_ -= f.size();
      queue_.pop_front();
      front_offset_ = 0;
    }
  }
  return true;
}

}  // namespace knoblab::control::detail
