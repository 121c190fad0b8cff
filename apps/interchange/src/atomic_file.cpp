#include "knoblab/interchange/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <fstream>
#include <string>
#include <system_error>

namespace knoblab::interchange {

namespace {
[[noreturn]] void throw_errno(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}
}  // namespace

PendingFile::PendingFile(std::filesystem::path path) : path_(std::move(path)) {
  // Same directory, so rename() is atomic; O_EXCL so concurrent writers never share one.
  static std::atomic<unsigned> counter{0};
  tmp_ = path_.string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw_errno("cannot create " + tmp_.string());
  ::close(fd);
}

PendingFile::~PendingFile() {
  if (!done_) ::unlink(tmp_.c_str());
}

void PendingFile::commit() {
  // Data on disk before the rename makes it visible.
  int fd = ::open(tmp_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw_errno("cannot reopen " + tmp_.string());
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw_errno("fsync " + tmp_.string());
  if (::rename(tmp_.c_str(), path_.c_str()) != 0) throw_errno("cannot rename to " + path_.string());
  done_ = true;
  // Persist the rename itself; best effort (some filesystems refuse dir fsync).
  const auto dir = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  PendingFile pending(path);
  {
    std::ofstream out(pending.temporary(), std::ios::binary | std::ios::trunc);
    if (!out) throw_errno("cannot open " + pending.temporary().string());
    errno = 0;
    write(out);
    out.close();
    if (!out) {
      // errno says why the failed write failed (ENOSPC: "No space left on
      // device"), when the stream left it set.
      if (errno == 0) errno = EIO;
      throw_errno("cannot write " + path.string());
    }
  }
  pending.commit();
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, [&](std::ostream& out) { out.write(content.data(), static_cast<std::streamsize>(content.size())); });
}

}  // namespace knoblab::interchange
