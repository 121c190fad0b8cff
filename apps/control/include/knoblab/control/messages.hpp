// The messages of protocol v1 as C++ values, and their JSON envelopes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "knoblab/control/protocol.hpp"

namespace knoblab::control {

using ClientId = std::uint64_t;  // per server run, never reused

// A request that passed the schema: `args` holds exactly the documented keys
// with the documented types and ranges (absent optional keys stay absent).
struct Request {
  std::int64_t id = 0;
  Command command = Command::ping;
  nlohmann::json args = nlohmann::json::object();
  ClientId client = 0;
};

struct Error {
  ErrorCode code = ErrorCode::internal;
  std::string message;  // for humans
  std::string key;      // bad_args: the offending key path ("pid.Kp"); else empty
};

struct Reply {
  bool ok = true;
  nlohmann::json result = nlohmann::json::object();  // ok: an object
  Error error{};                                    // !ok

  static Reply success(nlohmann::json result = nlohmann::json::object());
  static Reply failure(ErrorCode code, std::string message, std::string key = {});
};

// A message the server refuses before it becomes a Request; id is the
// request's id when it could be read, else the reply carries "id": null.
struct Rejection {
  std::optional<std::int64_t> id;
  Error error;
};

struct Event {
  std::string name;  // one of kEventNames
  nlohmann::json data = nlohmann::json::object();
};

// Envelopes, as sent on the wire.
nlohmann::json request_message(std::int64_t id, std::string_view cmd, nlohmann::json args);
nlohmann::json reply_message(std::optional<std::int64_t> id, const Reply& reply);
nlohmann::json event_message(const Event& event);

// What a client receives: a reply (id empty when the server could not read
// one) or an event. Throws std::runtime_error if the message breaks v1.
struct ReplyMessage {
  std::optional<std::int64_t> id;
  Reply reply;
};
using ServerMessage = std::variant<ReplyMessage, Event>;
ServerMessage parse_server_message(const nlohmann::json& message);

}  // namespace knoblab::control
