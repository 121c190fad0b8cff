// Cheap checks on a frame's payload before it reaches the JSON parser.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace knoblab::control::detail {

// Offset of the first byte that is not well-formed UTF-8 (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF), or nullopt.
std::optional<std::size_t> first_invalid_utf8(std::string_view bytes) noexcept;

// True if arrays/objects nest deeper than max_depth. Brackets inside strings
// do not count. Linear, no recursion: safe on any input.
bool nests_deeper_than(std::string_view json, int max_depth) noexcept;

}  // namespace knoblab::control::detail
