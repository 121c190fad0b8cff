// What a frame gets once it is complete: a rejection, the server's own
// answer (hello, ping, subscribe), or the CommandHandler's.
#include <algorithm>
#include <stdexcept>

#include "knoblab/control/decode.hpp"
#include "server_impl.hpp"

namespace knoblab::control {

using nlohmann::json;
using std::chrono::milliseconds;

void Server::Impl::answer(Connection& c, std::string_view payload) {
  auto decoded = decode_request(payload);
  if (auto* rejection = std::get_if<Rejection>(&decoded)) {
    ++counters.rejections;
    send(c, rejection->id,
         Reply::failure(rejection->error.code, std::move(rejection->error.message), std::move(rejection->error.key)));
    return;
  }
  auto& request = std::get<Request>(decoded);
  request.client = c.id();
  ++counters.requests;
  const auto now = Clock::now();
  c.last_request = now;  // only valid requests keep a connection alive: noise does not
  watchdog.feed(c.id(), now);
  send(c, request.id, dispatch(c, request));
}

Reply Server::Impl::dispatch(Connection& c, const Request& r) {
  switch (r.command) {
    case Command::hello: return hello(c, r);
    case Command::ping: return Reply::success();
    case Command::subscribe: return subscribe(c, r);
    default: break;
  }
  try {
    Reply reply = handler.handle(r);
    if (reply.ok && !reply.result.is_object())
      return Reply::failure(ErrorCode::internal, "handler returned a non-object result");
    return reply;
  } catch (const std::exception& e) {
    log(std::string("handler failed on ") + std::string(to_string(r.command)) + ": " + e.what());
    return Reply::failure(ErrorCode::internal, std::string("handler failed: ") + e.what());
  } catch (...) {
    return Reply::failure(ErrorCode::internal, "handler failed");
  }
}

Reply Server::Impl::hello(Connection& c, const Request& r) {
  const auto& versions = r.args.at("versions");
  if (std::find(versions.begin(), versions.end(), json(kProtocolVersion)) == versions.end())
    return Reply::failure(ErrorCode::unsupported_version,
                          "no common version: client speaks " + versions.dump() + ", server speaks [1]");
  json result = {{"version", kProtocolVersion},
                 {"server", config.server_name},
                 {"max_frame_bytes", kMaxFramePayload},
                 {"client_id", c.id()}};
  if (const auto wd = r.args.find("watchdog_ms"); wd != r.args.end()) {
    const milliseconds period(wd->get<std::int64_t>());
    if (!watchdog.arm(c.id(), period, Clock::now()))
      return Reply::failure(ErrorCode::busy, "another client (id " + std::to_string(*watchdog.supervisor()) +
                                                 ") already supervises the device");
    result["watchdog_ms"] = period.count();
  } else {
    watchdog.release(c.id());
  }
  result["supervising"] = watchdog.supervised_by(c.id());
  return Reply::success(std::move(result));
}

Reply Server::Impl::subscribe(Connection& c, const Request& r) {
  c.subscriptions.reset();
  for (const auto& e : r.args.at("events")) {
    const auto& name = e.get_ref<const std::string&>();
    if (name == "*") c.subscriptions.set();
    else c.subscriptions.set(*event_index(name));
  }
  json names = json::array();
  for (std::size_t i = 0; i < kEventNames.size(); ++i)
    if (c.subscriptions.test(i)) names.push_back(kEventNames[i]);
  json result = {{"events", std::move(names)}};
  if (r.args.value("telemetry", false)) result["telemetry_shm"] = config.telemetry_shm;
  return Reply::success(std::move(result));
}

void Server::Impl::watchdog_fired(WatchdogReason reason) {
  ++counters.watchdog_expiries;
  const char* why = reason == WatchdogReason::silence ? "silence" : "disconnect";
  log(std::string("watchdog expired (") + why + ")");
  try {
    handler.on_watchdog_expired(reason);
  } catch (const std::exception& e) {
    log(std::string("on_watchdog_expired failed: ") + e.what());
  } catch (...) {
    log("on_watchdog_expired failed");
  }
  const auto index = *event_index("watchdog_expired");
  broadcast(index, make_frame(event_message(
                       {"watchdog_expired", {{"reason", why}, {"watchdog_ms", watchdog.period().count()}}})));
}

}  // namespace knoblab::control
