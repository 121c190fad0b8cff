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

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  // Same directory, so rename() is atomic; O_EXCL so concurrent writers never share one.
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path tmp =
      path.string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw_errno("cannot create " + tmp.string());
  ::close(fd);

  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw_errno("cannot open " + tmp.string());
      write(out);
      out.close();
      if (!out) throw std::system_error(std::make_error_code(std::errc::io_error), "writing " + tmp.string());
    }
    // Data on disk before the rename makes it visible.
    fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw_errno("cannot reopen " + tmp.string());
    const int rc = ::fsync(fd);
    ::close(fd);
    if (rc != 0) throw_errno("fsync " + tmp.string());
    if (::rename(tmp.c_str(), path.c_str()) != 0) throw_errno("cannot rename to " + path.string());
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  // Persist the rename itself; best effort (some filesystems refuse dir fsync).
  const auto dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path, [&](std::ostream& out) { out.write(content.data(), static_cast<std::streamsize>(content.size())); });
}

}  // namespace knoblab::interchange
