#include "knoblab/control/messages.hpp"

#include <stdexcept>

namespace knoblab::control {

using nlohmann::json;

Reply Reply::success(json result) {
  Reply r;
  r.result = std::move(result);
  return r;
}

Reply Reply::failure(ErrorCode code, std::string message, std::string key) {
  Reply r;
  r.ok = false;
  r.result = nullptr;
  r.error = {code, std::move(message), std::move(key)};
  return r;
}

json request_message(std::int64_t id, std::string_view cmd, json args) {
  return {{"v", kProtocolVersion}, {"id", id}, {"cmd", cmd}, {"args", std::move(args)}};
}

json reply_message(std::optional<std::int64_t> id, const Reply& reply) {
  json m = {{"v", kProtocolVersion}, {"id", id ? json(*id) : json(nullptr)}, {"ok", reply.ok}};
  if (reply.ok) {
    m["result"] = reply.result;
  } else {
    json e = {{"code", to_string(reply.error.code)}, {"message", reply.error.message}};
    if (!reply.error.key.empty()) e["key"] = reply.error.key;
    m["error"] = std::move(e);
  }
  return m;
}

json event_message(const Event& event) {
  return {{"v", kProtocolVersion}, {"event", event.name}, {"data", event.data}};
}

namespace {

[[noreturn]] void violation(const std::string& what) {
  throw std::runtime_error("server message breaks protocol v1: " + what);
}

}  // namespace

ServerMessage parse_server_message(const json& m) {
  if (!m.is_object()) violation("not an object");
  const auto v = m.find("v");
  if (v == m.end() || !v->is_number_integer() || v->get<std::int64_t>() != kProtocolVersion)
    violation("missing or wrong \"v\"");

  if (const auto ev = m.find("event"); ev != m.end()) {
    if (!ev->is_string()) violation("\"event\" is not a string");
    const auto data = m.find("data");
    if (data == m.end() || !data->is_object()) violation("event without object \"data\"");
    return Event{ev->get<std::string>(), *data};
  }

  ReplyMessage out;
  const auto id = m.find("id");
  if (id == m.end()) violation("reply without \"id\"");
  if (id->is_number_integer()) out.id = id->get<std::int64_t>();
  else if (!id->is_null()) violation("\"id\" is neither an integer nor null");

  const auto ok = m.find("ok");
  if (ok == m.end() || !ok->is_boolean()) violation("reply without boolean \"ok\"");
  if (ok->get<bool>()) {
    const auto result = m.find("result");
    if (result == m.end() || !result->is_object()) violation("ok reply without object \"result\"");
    out.reply = Reply::success(*result);
    return out;
  }
  const auto err = m.find("error");
  if (err == m.end() || !err->is_object()) violation("error reply without object \"error\"");
  const auto code = err->find("code");
  const auto message = err->find("message");
  if (code == err->end() || !code->is_string()) violation("error without string \"code\"");
  if (message == err->end() || !message->is_string()) violation("error without string \"message\"");
  const auto parsed = error_code_from_string(code->get<std::string>());
  if (!parsed) violation("unknown error code \"" + code->get<std::string>() + "\"");
  std::string key;
  if (const auto k = err->find("key"); k != err->end() && k->is_string()) key = k->get<std::string>();
  out.reply = Reply::failure(*parsed, message->get<std::string>(), std::move(key));
  return out;
}

}  // namespace knoblab::control
