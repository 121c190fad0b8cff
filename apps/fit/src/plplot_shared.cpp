#include "knoblab/fit/plplot_shared.hpp"

namespace knoblab::fit {

std::mutex& plplot_mutex() {
  static std::mutex m;
  return m;
}

std::string plplot_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    out += c;
    if (c == '#') out += '#';
  }
  return out;
}

}  // namespace knoblab::fit
