// From a frame's payload to a validated Request, or the reason it is refused.
// Pure (no I/O), so the server, the tests and the fuzzer share it.
#pragma once

#include <string_view>
#include <variant>

#include "knoblab/control/messages.hpp"

namespace knoblab::control {

// Checks in order: empty → bad_frame; not UTF-8 → bad_frame; nested deeper
// than kMaxJsonDepth or not JSON → bad_json; not an object → not_an_object;
// "v" missing/wrong → unsupported_version; envelope keys → bad_args;
// "cmd" unknown → unknown_command; args against the table → bad_args.
// Never throws for any input (std::bad_alloc aside).
std::variant<Request, Rejection> decode_request(std::string_view payload);

}  // namespace knoblab::control
