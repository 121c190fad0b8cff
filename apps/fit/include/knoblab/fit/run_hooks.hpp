// How a long computation (a fit, a discrepancy search) tells its caller
// where it is, and learns that it should stop. Both hooks are optional:
// without them a run goes to its end silently.
#pragma once

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string_view>

namespace knoblab::fit {

// Thrown out of a run whose RunHooks::cancelled said so: it returns nothing.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

struct RunHooks {
  // Called, from the calling thread, as a run enters a stage ("searching
  // detents", "fitting", …) and, with `done` of `total`, as it works through
  // one ("trying candidates, round 1", 3, 15); total 0: no count.
  std::function<void(std::string_view stage, std::size_t done, std::size_t total)> progress;
  // Polled between steps, and by every Ceres iteration (ceres_hooks.hpp);
  // once it answers true the run throws Cancelled.
  std::function<bool()> cancelled;

  void report(std::string_view stage, std::size_t done = 0, std::size_t total = 0) const {
    if (progress) progress(stage, done, total);
  }
  void check() const {
    if (cancelled && cancelled()) throw Cancelled();
  }
};

}  // namespace knoblab::fit
