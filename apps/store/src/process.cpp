// Is the process that began a capture still there?
#include <signal.h>

#include <cerrno>
#include <climits>
#include <fstream>

#include "internal.hpp"

namespace knoblab::store::detail {

bool process_alive(std::int64_t pid) {
  if (pid <= 0 || pid > INT_MAX) return false;
  if (::kill(static_cast<pid_t>(pid), 0) == 0) return true;
  return errno != ESRCH;  // EPERM: it exists, it just is not ours
}

// After a reboot a recorded pid may belong to some unrelated process; the
// boot id tells that case apart.
std::string boot_id() {
  std::ifstream in("/proc/sys/kernel/random/boot_id");
  std::string id;
  std::getline(in, id);
  return id;
}

}  // namespace knoblab::store::detail
