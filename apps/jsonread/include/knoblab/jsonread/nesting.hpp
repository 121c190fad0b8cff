// How deep a JSON text nests, found before anything parses it. Documents
// people write (hapticd's config, study protocols, designs) nest a handful of
// levels; one nested hundreds of thousands deep is a mistake or an attack, and
// the recursion that builds, walks or destroys it overflows the stack.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace knoblab::jsonread {

// Deeper than any document of ours needs by far (they reach 8).
inline constexpr int kMaxNesting = 64;

// Why `text` nests too deep ("nested deeper than 64 levels at byte 1234"),
// or nothing. Counts brackets outside strings only; whether the text is
// JSON at all is the parser's to say afterwards.
std::optional<std::string> nesting_problem(std::string_view text, int max_depth = kMaxNesting);

}  // namespace knoblab::jsonread
