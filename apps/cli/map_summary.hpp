// What a static map holds at a glance, and its angular spectrum: the
// strongest whole-number harmonics of torque over one revolution (cogging,
// detents), each fitted on its own.
#pragma once

#include <cstddef>
#include <vector>

#include "knoblab/interchange/static_map.hpp"

namespace knoblab::cli {

struct Harmonic {
  int cycles_per_rev = 0;
  double amplitude = 0;  // N·m
  double power = 0;      // fraction of torque variance it explains alone
};

struct MapSummary {
  std::size_t points = 0;
  double theta_min = 0, theta_max = 0;  // rad
  double spacing = 0;                   // rad, median between neighbouring points
  double torque_min = 0, torque_max = 0, torque_mean = 0, torque_rms = 0;  // N·m
  // Strongest first; whole numbers of cycles per revolution from 1 up to what
  // the point spacing resolves (half the points per revolution, at most 1024).
  std::vector<Harmonic> harmonics;
};

MapSummary summarize_map(const interchange::StaticMap& map, std::size_t max_harmonics = 8);

}  // namespace knoblab::cli
