// A rendering's term by the name a matching slider gives it (protocol.hpp's
// Slider::parameter: M_acc, B_vel, A_pos, detents_per_rev — the only four the
// protocol reader admits).
#pragma once

#include <stdexcept>
#include <string>

#include "knoblab/study/protocol.hpp"

namespace knoblab::studyrun {

template <typename R>  // study::Rendering, const or not
auto& rendering_field(R& r, const std::string& parameter) {
  if (parameter == "M_acc") return r.M_acc;
  if (parameter == "B_vel") return r.B_vel;
  if (parameter == "A_pos") return r.A_pos;
  if (parameter == "detents_per_rev") return r.detents_per_rev;
  throw std::invalid_argument("no rendering term " + parameter);
}

}  // namespace knoblab::studyrun
