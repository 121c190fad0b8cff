// Text that reaches the store and JSON must be valid UTF-8: where it is not.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace knoblab::interchange {

// The offset of the first byte that does not start or continue a valid UTF-8
// sequence (overlong forms, surrogates and code points past U+10FFFF included),
// or nullopt when the whole text is valid.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

// The offset of the first control character (C0, DEL; tab included), if any.
std::optional<std::size_t> first_control_char(std::string_view text);

}  // namespace knoblab::interchange
