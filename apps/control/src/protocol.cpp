#include "knoblab/control/protocol.hpp"

namespace knoblab::control {

namespace {

constexpr std::array<std::string_view, kErrorCodeCount> kErrorNames = {
    "bad_frame",        "oversized",       "bad_json", "not_an_object", "unsupported_version",
    "unknown_command",  "bad_args",        "busy",     "internal"};

constexpr std::array<std::string_view, kCommandCount> kCommandNames = {
    "hello",       "ping",         "get_state",  "load_model", "set_params",
    "start_capture", "stop_capture", "start_trial", "stop_trial", "calibrate",
    "accept_calibration", "load_tiles", "clear_fault", "set_mode", "subscribe"};

static_assert(static_cast<std::size_t>(ErrorCode::internal) + 1 == kErrorCodeCount);
static_assert(static_cast<std::size_t>(Command::subscribe) + 1 == kCommandCount);

template <typename Enum, std::size_t N>
std::optional<Enum> lookup(const std::array<std::string_view, N>& names, std::string_view name) {
  for (std::size_t i = 0; i < N; ++i)
    if (names[i] == name) return static_cast<Enum>(i);
  return std::nullopt;
}

}  // namespace

std::string_view to_string(ErrorCode code) noexcept {
  return kErrorNames[static_cast<std::size_t>(code)];
}

std::optional<ErrorCode> error_code_from_string(std::string_view name) noexcept {
  return lookup<ErrorCode>(kErrorNames, name);
}

std::string_view to_string(Command command) noexcept {
  return kCommandNames[static_cast<std::size_t>(command)];
}

std::optional<Command> command_from_string(std::string_view name) noexcept {
  return lookup<Command>(kCommandNames, name);
}

bool handled_by_server(Command command) noexcept {
  return command == Command::hello || command == Command::ping || command == Command::subscribe;
}

std::optional<std::size_t> event_index(std::string_view name) noexcept {
  for (std::size_t i = 0; i < kEventNames.size(); ++i)
    if (kEventNames[i] == name) return i;
  return std::nullopt;
}

}  // namespace knoblab::control
