#include "shm_region.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "unique_fd.hpp"

namespace knoblab::control::detail {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what, int err) {
  throw std::runtime_error("telemetry shm " + name + ": " + what + ": " + std::strerror(err));
}

void check_name(const std::string& name) {
  if (name.size() < 2 || name[0] != '/' || name.find('/', 1) != std::string::npos || name.size() > 255)
    throw std::runtime_error("telemetry shm name '" + name + "' must be '/' followed by a name without '/'");
}

}  // namespace

ShmRegion ShmRegion::create(const std::string& name, std::size_t size, mode_t mode, std::optional<gid_t> gid) {
  check_name(name);
  UniqueFd fd(::shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, mode));
  if (!fd && errno == EEXIST) {
    // Left by a daemon that died (its lock went with it), or a running
    // daemon's: a second one started by mistake must not take it away.
    UniqueFd old(::shm_open(name.c_str(), O_RDONLY | O_CLOEXEC, 0));
    if (old && ::flock(old.get(), LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK)
      throw std::runtime_error("telemetry shm " + name + ": in use by a running daemon; not replacing it");
    // Readers still mapping the dead one keep the old object.
    ::shm_unlink(name.c_str());
    fd = UniqueFd(::shm_open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, mode));
  }
  if (!fd) fail(name, "shm_open", errno);
  if (::flock(fd.get(), LOCK_EX | LOCK_NB) != 0) fail(name, "flock", errno);

  ShmRegion r;
  r.unlink_name_ = name;  // from here on, failures unlink it again
  try {
    if (::fchmod(fd.get(), mode) != 0) fail(name, "fchmod", errno);  // umask must not narrow it
    if (gid && ::fchown(fd.get(), static_cast<uid_t>(-1), *gid) != 0) fail(name, "fchown", errno);
    if (::ftruncate(fd.get(), static_cast<off_t>(size)) != 0) fail(name, "ftruncate", errno);
    void* addr = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_POPULATE, fd.get(), 0);
    if (addr == MAP_FAILED) fail(name, "mmap", errno);
    r.addr_ = addr;
    r.size_ = size;
    r.owner_lock_ = std::move(fd);
  } catch (...) {
    ::shm_unlink(name.c_str());
    r.unlink_name_.clear();
    throw;
  }
  return r;
}

ShmRegion ShmRegion::open_read_only(const std::string& name) {
  check_name(name);
  UniqueFd fd(::shm_open(name.c_str(), O_RDONLY | O_CLOEXEC, 0));
  if (!fd) fail(name, "shm_open", errno);
  struct stat st{};
  if (::fstat(fd.get(), &st) != 0) fail(name, "fstat", errno);
  if (st.st_size <= 0) throw std::runtime_error("telemetry shm " + name + ": empty (daemon still starting?)");
  const auto size = static_cast<std::size_t>(st.st_size);
  void* addr = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd.get(), 0);
  if (addr == MAP_FAILED) fail(name, "mmap", errno);
  ShmRegion r;
  r.addr_ = addr;
  r.size_ = size;
  return r;
}

ShmRegion::ShmRegion(ShmRegion&& o) noexcept
    : addr_(std::exchange(o.addr_, nullptr)),
      size_(std::exchange(o.size_, 0)),
      unlink_name_(std::move(o.unlink_name_)),
      owner_lock_(std::move(o.owner_lock_)) {
  o.unlink_name_.clear();
}

ShmRegion& ShmRegion::operator=(ShmRegion&& o) noexcept {
  if (this != &o) {
    release();
    addr_ = std::exchange(o.addr_, nullptr);
    size_ = std::exchange(o.size_, 0);
    unlink_name_ = std::move(o.unlink_name_);
    o.unlink_name_.clear();
    owner_lock_ = std::move(o.owner_lock_);
  }
  return *this;
}

ShmRegion::~ShmRegion() { release(); }

void ShmRegion::release() noexcept {
  if (addr_) ::munmap(addr_, size_);
  if (!unlink_name_.empty()) ::shm_unlink(unlink_name_.c_str());
  owner_lock_.reset();  // after the unlink: no one may take the name while it is ours
  addr_ = nullptr;
  size_ = 0;
  unlink_name_.clear();
}

}  // namespace knoblab::control::detail
