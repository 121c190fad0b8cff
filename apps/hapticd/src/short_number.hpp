// A number as a refusal message shows it: four significant digits.
#pragma once

#include <cstdio>
#include <string>

namespace knoblab::hapticd::detail {

inline std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace knoblab::hapticd::detail
