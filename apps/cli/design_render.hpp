// A prototyper design played by hapticd's core on the sim plant in simulated
// time (as `knoblab simulate` runs a capture), while a simulated hand turns
// the knob slowly across the design's whole range and back: the recording
// shows what the design feels like, and a fit or a discrepancy run can be
// made of it. The design reaches the core exactly as `load_tiles` reaches
// hapticd: through its render model and hapticd's own checks.
#pragma once

#include <stdexcept>
#include <string>

#include "knoblab/design/design.hpp"
#include "knoblab/interchange/capture.hpp"

namespace knoblab::cli {

// What the capture's torque column holds.
enum class RenderedTorque {
  // The torque sensor's reading, as hapticd records it: the motor's push on
  // the knob, the opposite of the torque the design resists with.
  Sensor,
  // The torque it takes to turn the knob (the sensor's reading negated):
  // Eq. 6's sign, as a Haptic Camera turning the rendered knob records it,
  // and what knoblab fit and discrepancy read a knob's torque as.
  Knob,
};

struct DesignRenderRequest {
  design::Design design;
  double seconds = 20.0;
  double rate_hz = 10000.0;  // the thesis' prototyper knob ran at 10 kHz (§5.2.3)
  // The haptic knob's own mechanism on the motor, nothing rendered (Study 3).
  std::string knob = "study3-not-rendered";
  // A light grip (the sim backend's default hand, docs/hal.md).
  double grip_stiffness = 1.0;   // N·m/rad
  double grip_damping = 0.01;    // N·m·s/rad
  RenderedTorque torque = RenderedTorque::Sensor;
};

struct DesignRenderResult {
  interchange::Capture capture;  // every cycle
  double range_from = 0.0, range_to = 0.0;  // rad: where the hand turned the knob
};

// What hapticd at this loop rate would say to the design's render model: ""
// when it would play it.
std::string design_render_refusal(const design::Design& d, double rate_hz = 10000.0);

// Throws std::invalid_argument for a request or design hapticd would refuse
// (with its reason), std::runtime_error when the supervisor latched a fault
// (which, and when).
DesignRenderResult render_design(const DesignRenderRequest& request);

}  // namespace knoblab::cli
