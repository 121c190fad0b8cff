// Which client supervises, and when its silence expires. Pure bookkeeping
// on a caller-supplied clock, so the rules are easy to follow and test.
#pragma once

#include <chrono>
#include <optional>

#include "knoblab/control/command_handler.hpp"
#include "knoblab/control/messages.hpp"

namespace knoblab::control::detail {

class Watchdog {
 public:
  using Clock = std::chrono::steady_clock;

  std::optional<ClientId> supervisor() const { return supervisor_; }
  bool supervised_by(ClientId c) const { return supervisor_ == c; }

  // hello with watchdog_ms. False if another client already supervises.
  bool arm(ClientId c, std::chrono::milliseconds period, Clock::time_point now) {
    if (supervisor_ && *supervisor_ != c) return false;
    supervisor_ = c;
    period_ = period;
    deadline_ = now + period;
    return true;
  }
  // hello without watchdog_ms from the supervisor: ends supervision quietly.
  void release(ClientId c) {
    if (supervised_by(c)) supervisor_.reset();
  }
  // A valid request from c.
  void feed(ClientId c, Clock::time_point now) {
    if (supervised_by(c)) deadline_ = now + period_;
  }
  // True (and supervision ends) if c was the supervisor.
  bool disconnected(ClientId c) {
    if (!supervised_by(c)) return false;
    supervisor_.reset();
    return true;
  }
  // True (and supervision ends) if the supervisor's silence ran out.
  bool expired(Clock::time_point now) {
    if (!supervisor_ || now < deadline_) return false;
    supervisor_.reset();
    return true;
  }
  std::optional<Clock::time_point> deadline() const {
    return supervisor_ ? std::optional(deadline_) : std::nullopt;
  }
  std::chrono::milliseconds period() const { return period_; }

 private:
  std::optional<ClientId> supervisor_;
  std::chrono::milliseconds period_{0};
  Clock::time_point deadline_{};
};

}  // namespace knoblab::control::detail
