// Replacing a file so that a reader, a full disk, a killed process or a
// power cut never sees it half-written: write a temporary file beside it,
// fsync, rename over the old one, fsync the directory. Until the rename the
// old file is untouched.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace knoblab::interchange {

// `write` fills the stream; if it throws or the stream fails, the temporary
// file is removed and the old file stays. Throws std::system_error.
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace knoblab::interchange
