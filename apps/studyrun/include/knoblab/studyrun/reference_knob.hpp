// A matching study's reference knob as the terms its sliders set: the
// level's own rendering, or the sim preset it names read as Eq. 14 (mean of
// the two damping directions, detent amplitude and count). What the
// simulated participant matches, and what the report compares matches with.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "knoblab/study/protocol.hpp"

namespace knoblab::studyrun {

// None when the level has neither a rendering nor a known preset.
std::optional<study::Rendering> reference_rendering(const study::Level& level);

// Per level of the protocol's first factor (the knob), the reference values
// of its sliders' parameters: level → parameter → SI. Levels without a
// reference are left out.
std::map<std::string, std::map<std::string, double>> matching_references(const study::Protocol& protocol);

}  // namespace knoblab::studyrun
