// Protocol v1 constants shared by the server, the client and the docs
// (docs/protocol.md is the contract; this header is its vocabulary).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace knoblab::control {

inline constexpr int kProtocolVersion = 1;
// Frame = 4-byte big-endian payload length + payload (UTF-8 JSON object).
inline constexpr std::size_t kFrameHeaderBytes = 4;
inline constexpr std::size_t kMaxFramePayload = 64 * 1024;
// Nesting deeper than this is refused before parsing (nothing in v1 needs
// more than 4 levels; the limit protects the parser's stack).
inline constexpr int kMaxJsonDepth = 32;

// Wire names are the enumerator names.
enum class ErrorCode : std::uint8_t {
  bad_frame,            // empty frame, payload not UTF-8, frame left incomplete
  oversized,            // length header above kMaxFramePayload (connection closed)
  bad_json,             // payload is not JSON (or nested too deep)
  not_an_object,        // JSON, but not an object
  unsupported_version,  // "v" missing or not a version the server speaks
  unknown_command,      // "cmd" names no command
  bad_args,             // envelope or argument fails the schema (message names the key)
  busy,                 // refused for now: another client supervises, too many clients
                        // (or from one process), a silent connection closed to free its
                        // slot, or the daemon cannot do it in its current state
  internal,             // the daemon failed while handling a valid request
};
inline constexpr std::size_t kErrorCodeCount = 9;

std::string_view to_string(ErrorCode code) noexcept;
std::optional<ErrorCode> error_code_from_string(std::string_view name) noexcept;

// Every v1 command. Wire names are the enumerator names.
enum class Command : std::uint8_t {
  hello, ping, get_state, load_model, set_params, start_capture, stop_capture,
  start_trial, stop_trial, calibrate, accept_calibration, load_tiles, clear_fault, set_mode,
  subscribe,
};
inline constexpr std::size_t kCommandCount = 15;

std::string_view to_string(Command command) noexcept;
std::optional<Command> command_from_string(std::string_view name) noexcept;
// hello, ping and subscribe are answered by the server itself; the rest go
// to the CommandHandler.
bool handled_by_server(Command command) noexcept;

// Event names a client can subscribe to ("*" subscribes to all).
inline constexpr std::array<std::string_view, 8> kEventNames = {
    "state", "fault_latched", "capture_finished", "trial", "calibration_finished",
    "stats", "watchdog_expired", "capture_button"};
std::optional<std::size_t> event_index(std::string_view name) noexcept;

}  // namespace knoblab::control
