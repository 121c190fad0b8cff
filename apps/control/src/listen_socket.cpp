#include "listen_socket.hpp"

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "group_lookup.hpp"

namespace knoblab::control::detail {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
  throw std::runtime_error("control socket " + path + ": " + what + ": " + std::strerror(err));
}

sockaddr_un address_of(const std::string& path) {
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof addr.sun_path)
    throw std::runtime_error("control socket path '" + path + "' is empty or longer than " +
                             std::to_string(sizeof addr.sun_path - 1) + " bytes");
  std::memcpy(addr.sun_path, path.c_str(), path.size() + 1);
  return addr;
}

void make_parent_dirs(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos || slash == 0) return;
  const std::string parent = path.substr(0, slash);
  for (std::size_t pos = 0; pos != std::string::npos;) {
    pos = parent.find('/', pos + 1);
    const std::string dir = parent.substr(0, pos);
    if (::mkdir(dir.c_str(), 0755) == 0 || errno == EEXIST) continue;
    fail(path, "cannot create directory " + dir, errno);
  }
  struct stat st{};
  if (::stat(parent.c_str(), &st) != 0) fail(path, "cannot stat " + parent, errno);
  if (!S_ISDIR(st.st_mode)) throw std::runtime_error("control socket " + path + ": " + parent + " is not a directory");
}

// A socket file nobody answers on is left over from a dead server.
void remove_if_stale(const std::string& path, const sockaddr_un& addr) {
  struct stat st{};
  if (::lstat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    fail(path, "cannot stat", errno);
  }
  if (!S_ISSOCK(st.st_mode))
    throw std::runtime_error("control socket " + path + ": exists and is not a socket; refusing to remove it");
  UniqueFd probe(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!probe) fail(path, "socket()", errno);
  if (::connect(probe.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0)
    throw std::runtime_error("control socket " + path + ": in use by a running server");
  if (errno != ECONNREFUSED) fail(path, "cannot probe existing socket", errno);
  if (::unlink(path.c_str()) != 0 && errno != ENOENT) fail(path, "cannot remove stale socket", errno);
}

}  // namespace

ListeningSocket open_listening_socket(const std::string& path, const std::string& group) {
  const sockaddr_un addr = address_of(path);
  const std::optional<gid_t> gid = required_group(group, "control socket " + path);
  make_parent_dirs(path);
  remove_if_stale(path, addr);

  ListeningSocket ls;
  ls.fd = UniqueFd(::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
  if (!ls.fd) fail(path, "socket()", errno);
  if (::bind(ls.fd.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) fail(path, "bind", errno);
  try {
    if (::chmod(path.c_str(), 0660) != 0) fail(path, "chmod 0660", errno);
    if (gid && ::chown(path.c_str(), static_cast<uid_t>(-1), *gid) != 0)
      fail(path, "chown to group '" + group + "'", errno);
    struct stat st{};
    if (::stat(path.c_str(), &st) != 0) fail(path, "cannot stat after bind", errno);
    ls.dev = st.st_dev;
    ls.ino = st.st_ino;
    if (::listen(ls.fd.get(), 64) != 0) fail(path, "listen", errno);
  } catch (...) {
    ::unlink(path.c_str());
    throw;
  }
  return ls;
}

void remove_socket_file(const std::string& path, dev_t dev, ino_t ino) noexcept {
  struct stat st{};
  if (::lstat(path.c_str(), &st) == 0 && st.st_dev == dev && st.st_ino == ino) ::unlink(path.c_str());
}

}  // namespace knoblab::control::detail
