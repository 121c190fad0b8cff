// What the participant's screen shows during a trial, as the runner's tasks
// set it: the participant view draws it, the simulated participant reacts to
// it. Angles are the knob's, SI (rad).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "knoblab/study/protocol.hpp"

namespace knoblab::studyrun {

struct Disk {
  double centre_rad = 0;
  double width_rad = 0;
  bool contains(double theta) const { return theta >= centre_rad - width_rad / 2 && theta <= centre_rad + width_rad / 2; }
  bool operator==(const Disk&) const = default;
};

struct Display {
  std::uint64_t version = 0;  // counts changes, so a viewer redraws only when it changed
  std::string instruction;    // one short sentence for the participant
  // Pointing: the disk to acquire (the home disk, then each target); the
  // needle follows the knob.
  std::optional<Disk> disk;
  bool needle = false;
  // List selection: the counter the knob moves and the value to find; both
  // empty while the display is off (freeform exploration).
  std::optional<long> counter;
  std::optional<long> target_value;
  // Matching: the rendered knob's slider values and the reference knob's
  // name; textures: the texture being presented.
  std::optional<study::Rendering> sliders;
  std::string reference;
  bool operator==(const Display&) const = default;
};

}  // namespace knoblab::studyrun
