// The thesis' simulated validation data (§2.1.2): the swept sine of Eq. 8
// with Eq. 9's constants, torque by Eq. 10 and uniform noise by Eq. 11.
#pragma once

#include <cstdint>
#include <vector>

#include "knoblab/fit/fit_data.hpp"

namespace knoblab::fit {

struct ValidationSpec {
  double rate_hz = 5000.0;
  std::size_t samples = 30000;  // t_n = n / rate, n = 1 … samples
  double a = 0.0, b = 1.5, c = 1.0, d = 3.0;  // Eq. 9
  // Eq. 10, in model::ThesisParam order.
  std::vector<double> params = {0.4, 1.5, 1.0, 2.0, 1.5, 1.0, 0.2, 0.9};
  double noise_peak_to_peak = 4.0;  // Eq. 11: 4.0·(rand − 0.5)
  std::uint64_t seed = 1;
};

// Exact kinematics (analytic derivatives of Eq. 8) and noisy torque.
FitData make_validation_data(const ValidationSpec& spec);

}  // namespace knoblab::fit
