#include "knoblab/control/decode.hpp"

#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "knoblab/control/schema.hpp"
#include "payload_checks.hpp"

namespace knoblab::control {

using nlohmann::json;

namespace {

// Parser messages quote input; keep replies short.
std::string clipped(std::string s, std::size_t max = 200) {
  if (s.size() > max) {
    s.resize(max);
    s += "…";
  }
  return s;
}

Rejection reject(std::optional<std::int64_t> id, ErrorCode code, std::string message, std::string key = {}) {
  return Rejection{id, Error{code, std::move(message), std::move(key)}};
}

std::optional<std::int64_t> read_id(const json& m) {
  const auto it = m.find("id");
  if (it == m.end() || !it->is_number_integer()) return std::nullopt;
  if (it->is_number_unsigned() &&
      it->get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    return std::nullopt;
  return it->get<std::int64_t>();
}

}  // namespace

std::variant<Request, Rejection> decode_request(std::string_view payload) {
  if (payload.empty()) return reject(std::nullopt, ErrorCode::bad_frame, "empty frame");
  if (const auto bad = detail::first_invalid_utf8(payload))
    return reject(std::nullopt, ErrorCode::bad_frame,
                  "payload is not valid UTF-8 (byte " + std::to_string(*bad) + ")");
  if (detail::nests_deeper_than(payload, kMaxJsonDepth))
    return reject(std::nullopt, ErrorCode::bad_json,
                  "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");

  json m;
  try {
    m = json::parse(payload);
  } catch (const json::exception& e) {
    return reject(std::nullopt, ErrorCode::bad_json, clipped(e.what()));
  }
  if (!m.is_object()) return reject(std::nullopt, ErrorCode::not_an_object, "a message must be a JSON object");

  const auto id = read_id(m);
  const auto v = m.find("v");
  if (v == m.end())
    return reject(id, ErrorCode::unsupported_version, "missing \"v\"; this server speaks v1");
  if (!v->is_number_integer() || *v != kProtocolVersion)
    return reject(id, ErrorCode::unsupported_version, "\"v\": " + clipped(v->dump()) + " is not supported; this server speaks v1");

  for (const auto& [k, val] : m.items())
    if (k != "v" && k != "id" && k != "cmd" && k != "args")
      return reject(id, ErrorCode::bad_args, "unknown request key '" + clipped(k, 64) + "'", clipped(k, 64));
  if (!id) return reject(std::nullopt, ErrorCode::bad_args, "\"id\" must be an integer (int64)", "id");

  const auto cmd = m.find("cmd");
  if (cmd == m.end() || !cmd->is_string())
    return reject(id, ErrorCode::bad_args, "\"cmd\" must be a string", "cmd");
  const auto command = command_from_string(cmd->get_ref<const std::string&>());
  if (!command)
    return reject(id, ErrorCode::unknown_command, "unknown command '" + clipped(cmd->get<std::string>(), 64) + "'");

  Request r;
  r.id = *id;
  r.command = *command;
  if (const auto args = m.find("args"); args != m.end()) {
    if (!args->is_object()) return reject(id, ErrorCode::bad_args, "\"args\" must be an object", "args");
    r.args = std::move(*args);
  }
  if (const auto p = validate_args(r.args, command_spec(*command).args))
    return reject(id, ErrorCode::bad_args, "argument '" + clipped(p->key, 64) + "' " + p->problem,
                  clipped(p->key, 64));
  return r;
}

}  // namespace knoblab::control
