// What hapticd implements to serve the protocol. The server calls it on its
// own (non-realtime) thread, one call at a time, only with requests that
// passed the schema; a call blocks every client, so keep it short.
#pragma once

#include "knoblab/control/messages.hpp"

namespace knoblab::control {

enum class WatchdogReason { silence, disconnect };

class CommandHandler {
 public:
  virtual ~CommandHandler() = default;

  // Every command except hello, ping and subscribe (the server answers
  // those). Return Reply::success(result object) or Reply::failure(code,
  // message) — typically busy, or bad_args for a combination the schema
  // cannot express. An exception becomes an `internal` error reply.
  virtual Reply handle(const Request& request) = 0;

  // The supervising client went silent for its watchdog_ms, or disconnected:
  // put the motor in its safe state. Called once per expiry; supervision then
  // ends until a client says hello with watchdog_ms again.
  virtual void on_watchdog_expired(WatchdogReason reason) = 0;
};

}  // namespace knoblab::control
