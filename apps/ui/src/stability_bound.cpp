#include "stability_bound.hpp"

#include <algorithm>

#include "knoblab/model/render_stability.hpp"

namespace knoblab::ui {

StabilityBound stability_bound(double rate_hz) {
  model::LoopDynamics d;
  d.rate_hz = rate_hz;
  // As hapticd's sensor front end filters the render velocity (SensorConfig:
  // order 10, 500 Hz, at most a fifth of the rate).
  d.velocity_filter_order = 10;
  d.velocity_cutoff_hz = std::min(500.0, 0.2 * rate_hz);
  const model::LoopStability loop(d);
  return {loop.max_damping(0.0), loop.max_stiffness(0.0)};
}

}  // namespace knoblab::ui
