#include "knoblab/hal/shared_hand_channel.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <new>
#include <stdexcept>
#include <type_traits>

namespace knoblab::hal {

namespace {

static_assert(std::is_standard_layout_v<sim::HandChannel>);

[[noreturn]] void fail(const std::string& name, const char* what, int err) {
  throw std::runtime_error("hand channel " + name + ": " + what + ": " + std::strerror(err));
}

}  // namespace

SharedHandChannel::SharedHandChannel(const std::string& name) {
  if (name.size() < 2 || name[0] != '/' || name.find('/', 1) != std::string::npos || name.size() > 255)
    throw std::runtime_error("hand channel name '" + name + "' must be '/' followed by a name without '/'");
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0660);
  if (fd < 0) fail(name, "shm_open", errno);
  struct stat st{};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    fail(name, "fstat", err);
  }
  const auto size = static_cast<off_t>(sizeof(sim::HandChannel));
  // A new object is all zeros, which is a channel with no command yet (the
  // hand is off the knob); an existing one is used as it is.
  if (st.st_size < size && ::ftruncate(fd, size) != 0) {
    const int err = errno;
    ::close(fd);
    fail(name, "ftruncate", err);
  }
  void* p = ::mmap(nullptr, sizeof(sim::HandChannel), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  const int err = errno;
  ::close(fd);
  if (p == MAP_FAILED) fail(name, "mmap", err);
  // Zero bytes are a valid HandChannel of lock-free atomics; start its
  // lifetime in this process without writing to it.
  channel_ = std::launder(reinterpret_cast<sim::HandChannel*>(p));
  mapping_ = std::shared_ptr<void>(p, [](void* q) { ::munmap(q, sizeof(sim::HandChannel)); });
}

}  // namespace knoblab::hal
