// Helpers shared by the store's source files; not part of the API.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "knoblab/store/sqlite.hpp"
#include "knoblab/store/types.hpp"

namespace knoblab::store::detail {

// process.cpp
bool process_alive(std::int64_t pid);  // kill(pid, 0) does not say ESRCH
std::string boot_id();                 // this boot's id, "" if unknown

// store.cpp: call inside a write transaction. `created` (when given) tells
// whether the knob was inserted just now.
std::optional<std::int64_t> resolve_knob(sqlite::Connection& db, std::string_view name,
                                         std::string_view description = {},
                                         bool* created = nullptr);
// Inserts the captures row; recording rows carry our pid and boot id.
std::int64_t insert_capture_row(sqlite::Connection& db, const NewCapture& info,
                                std::string_view status, bool has_command,
                                bool* created_knob = nullptr);

// load.cpp: SELECT list matching read_capture_row, for "FROM captures c".
extern const char* const kCaptureColumns;
CaptureInfo read_capture_row(const sqlite::Statement& st);

}  // namespace knoblab::store::detail
