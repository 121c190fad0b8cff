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

// The same for a writer that opens the file itself (a plotting library):
// write temporary(), then commit(). Destroyed uncommitted (an exception, an
// early return), it removes the temporary file and the old one stays.
class PendingFile {
 public:
  explicit PendingFile(std::filesystem::path path);  // creates temporary(), empty
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::filesystem::path& temporary() const { return tmp_; }
  // fsync, rename over the path, fsync the directory. Throws std::system_error.
  void commit();

 private:
  std::filesystem::path path_, tmp_;
  bool done_ = false;
};

}  // namespace knoblab::interchange
