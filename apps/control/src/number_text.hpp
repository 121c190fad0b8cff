// Shortest round-trip text of a double, for messages and docs.
#pragma once

#include <charconv>
#include <string>

namespace knoblab::control::detail {

inline std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace knoblab::control::detail
