// A mapped POSIX shared-memory object: created and unlinked by its owner
// (the daemon), or opened read-only by readers.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <optional>
#include <string>

#include "unique_fd.hpp"

namespace knoblab::control::detail {

class ShmRegion {
 public:
  // Replaces any leftover object of that name (a dead daemon's), sizes it,
  // sets mode and group, and maps it read-write with its pages populated so
  // the realtime writer never page-faults on first touch. The owner holds
  // an exclusive flock on it while it lives: an object whose lock is held
  // belongs to a running daemon and is refused, never removed.
  static ShmRegion create(const std::string& name, std::size_t size, mode_t mode, std::optional<gid_t> gid);
  // Maps an existing object read-only.
  static ShmRegion open_read_only(const std::string& name);

  ShmRegion(ShmRegion&& o) noexcept;
  ShmRegion& operator=(ShmRegion&& o) noexcept;
  ShmRegion(const ShmRegion&) = delete;
  ShmRegion& operator=(const ShmRegion&) = delete;
  ~ShmRegion();

  void* data() const noexcept { return addr_; }
  std::size_t size() const noexcept { return size_; }

 private:
  ShmRegion() = default;
  void release() noexcept;

  void* addr_ = nullptr;
  std::size_t size_ = 0;
  std::string unlink_name_;  // set for the owner
  UniqueFd owner_lock_;      // the owner's open fd, flocked exclusively
};

}  // namespace knoblab::control::detail
