// Numbers as text: the shortest form that reads back as the same double, so
// files and JSON knoblab writes lose nothing and stay short.
#pragma once

#include <charconv>
#include <string>

namespace knoblab::interchange {

inline std::string shortest(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace knoblab::interchange
