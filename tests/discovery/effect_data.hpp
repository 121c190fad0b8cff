// The thesis' validation data (Eq. 8–11, swept over ±4 rad instead of ±1 so
// that once-per-revolution and unrelated periods are resolvable) with extra
// torque added: an effect concealed at about the noise's size.
#pragma once

#include <cstdint>
#include <functional>

#include "knoblab/fit/validation_data.hpp"

namespace knoblab::discovery::test_data {

// Validation data (uniform noise, SD 1.15 N·m) with `extra` added to the torque.
inline fit::FitData with_effect(std::uint64_t seed,
                                const std::function<double(const fit::FitData&, std::size_t)>& extra) {
  fit::ValidationSpec spec;
  spec.seed = seed;
  spec.c = 4.0;  // sweep amplitude, rad
  fit::FitData d = fit::make_validation_data(spec);
  if (extra)
    for (std::size_t i = 0; i < d.size(); ++i) d.torque[i] += extra(d, i);
  return d;
}

}  // namespace knoblab::discovery::test_data
