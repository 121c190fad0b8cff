// Group name → gid with getgrnam_r (thread-safe, unlike getgrnam).
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>

namespace knoblab::control::detail {

// nullopt if no such group; throws std::system_error if the lookup fails.
std::optional<gid_t> lookup_group(const std::string& name);

// The gid to chown to: nullopt for an empty name ("keep"); throws
// std::runtime_error naming `what` if the group does not exist.
std::optional<gid_t> required_group(const std::string& name, const std::string& what);

}  // namespace knoblab::control::detail
