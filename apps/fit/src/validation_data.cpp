#include "knoblab/fit/validation_data.hpp"

#include <random>
#include <stdexcept>

#include "knoblab/model/models.hpp"
#include "knoblab/model/trajectory.hpp"

namespace knoblab::fit {

FitData make_validation_data(const ValidationSpec& spec) {
  if (spec.params.size() != model::kThesisParamCount) {
    throw std::invalid_argument("validation params need the 8 Eq. 6 values");
  }
  const model::SweptSine sweep{spec.a, spec.b, spec.c, spec.d};
  const auto m = model::ThesisModel<double>::from_params(spec.params.data());
  // mt19937_64 is fully specified by the standard; the uniform transform is
  // ours, so every platform draws the same noise for a seed.
  std::mt19937_64 engine(spec.seed);
  FitData d;
  d.rate_hz = spec.rate_hz;
  for (std::size_t n = 1; n <= spec.samples; ++n) {
    const double t = static_cast<double>(n) / spec.rate_hz;
    const model::Kinematics<double> k = sweep.at(t);
    const double rand = static_cast<double>(engine() >> 11) * 0x1.0p-53;
    d.t.push_back(t);
    d.theta.push_back(k.theta);
    d.omega.push_back(k.omega);
    d.alpha.push_back(k.alpha);
    d.torque.push_back(m.torque(k) + spec.noise_peak_to_peak * (rand - 0.5));
  }
  return d;
}

}  // namespace knoblab::fit
