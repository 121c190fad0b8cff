// Creating (and later removing) the server's socket file safely.
#pragma once

#include <sys/types.h>

#include <string>

#include "unique_fd.hpp"

namespace knoblab::control::detail {

struct ListeningSocket {
  UniqueFd fd;  // non-blocking, listening
  dev_t dev = 0;
  ino_t ino = 0;  // identity of the file we bound, so stop() removes only ours
};

// Creates missing parent directories (0755); removes a stale socket file
// left by a dead server, but refuses a path that is not a socket or that a
// live server still answers on; binds; sets mode 0660 and the group; only
// then listens, so nobody connects before the permissions are right.
ListeningSocket open_listening_socket(const std::string& path, const std::string& group);

// Unlinks `path` if it is still the socket file we created.
void remove_socket_file(const std::string& path, dev_t dev, ino_t ino) noexcept;

}  // namespace knoblab::control::detail
