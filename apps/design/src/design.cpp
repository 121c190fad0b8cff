#include "knoblab/design/design.hpp"

namespace knoblab::design {

std::string_view channel_name(Channel c) {
  switch (c) {
    case Channel::Position: return "position";
    case Channel::Velocity: return "velocity";
    case Channel::Acceleration: return "acceleration";
    case Channel::Time: return "time";
  }
  return "?";
}

std::string_view x_unit(Channel c) {
  switch (c) {
    case Channel::Velocity: return "rad/s";
    case Channel::Time: return "s";
    default: return "rad";
  }
}

std::string_view y_unit(Channel c) { return c == Channel::Acceleration ? "kg·m²" : "N·m"; }

}  // namespace knoblab::design
