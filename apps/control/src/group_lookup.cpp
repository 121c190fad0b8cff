#include "group_lookup.hpp"

#include <grp.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace knoblab::control::detail {

std::optional<gid_t> lookup_group(const std::string& name) {
  const long hint = ::sysconf(_SC_GETGR_R_SIZE_MAX);
  std::vector<char> buf(hint > 0 ? static_cast<std::size_t>(hint) : 1024);
  for (;;) {
    group grp{};
    group* result = nullptr;
    const int rc = ::getgrnam_r(name.c_str(), &grp, buf.data(), buf.size(), &result);
    if (rc == ERANGE && buf.size() < (1u << 20)) {  // large groups need more room
      buf.resize(buf.size() * 2);
      continue;
    }
    if (rc != 0) throw std::system_error(rc, std::generic_category(), "getgrnam_r(\"" + name + "\")");
    if (!result) return std::nullopt;
    return result->gr_gid;
  }
}

std::optional<gid_t> required_group(const std::string& name, const std::string& what) {
  if (name.empty()) return std::nullopt;
  const auto gid = lookup_group(name);
  if (!gid)
    throw std::runtime_error(what + ": group '" + name +
                             "' does not exist (create it, or configure an empty group to keep the current one)");
  return gid;
}

}  // namespace knoblab::control::detail
