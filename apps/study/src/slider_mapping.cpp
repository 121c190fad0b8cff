#include "knoblab/study/slider_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <stdexcept>

namespace knoblab::study {

namespace {

// A Slider built in code (not parsed) can hold anything: refuse what has no mapping.
void check_slider(const Slider& s) {
  if (!std::isfinite(s.min) || !std::isfinite(s.max) || !(s.max > s.min))
    throw std::invalid_argument(
        std::format("slider {}: its range must be finite with max above min, got {} to {}", s.parameter, s.min, s.max));
  if (!std::isfinite(s.perceptual_exponent) || !(s.perceptual_exponent > 0))
    throw std::invalid_argument(
        std::format("slider {}: perceptual_exponent must be above 0, got {}", s.parameter, s.perceptual_exponent));
}

}  // namespace

double slider_value(const Slider& s, double position) {
  check_slider(s);
  if (!std::isfinite(position))
    throw std::invalid_argument(std::format("slider {}: position must be finite, got {}", s.parameter, position));
  const double p = std::clamp(position, 0.0, 1.0);
  const double u = s.perceptual_exponent == 1 ? p : std::pow(p, 1.0 / s.perceptual_exponent);
  return std::clamp(s.min + (s.max - s.min) * u, s.min, s.max);
}

double slider_position(const Slider& s, double value) {
  check_slider(s);
  if (!std::isfinite(value))
    throw std::invalid_argument(std::format("slider {}: value must be finite, got {}", s.parameter, value));
  const double u = (std::clamp(value, s.min, s.max) - s.min) / (s.max - s.min);
  return std::clamp(s.perceptual_exponent == 1 ? u : std::pow(u, s.perceptual_exponent), 0.0, 1.0);
}

}  // namespace knoblab::study
