// One capture through the fitter: prepare (Table 6 filtering), fit, predict,
// and the outputs a fit can write. Shared by `knoblab fit` and the demo.
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/interchange/capture.hpp"

namespace knoblab::cli {

struct FitRun {
  fit::FitData data;
  fit::FitResult result;
};

FitRun fit_capture(const interchange::Capture& capture, const fit::PrepOptions& prep,
               const fit::FitOptions& options);

// The fitted parameters in presentation units (mN·m, rad; for a linear
// axis N, mm: fit/axis_units.hpp), with 95% CIs.
void print_fit(std::FILE* out, const fit::FitResult& r);

// A parameter's presentation unit and the factor from SI to it: torques in
// mN·m, angles in rad (Eq. 6's names, the stick band's dv, D_neg, D_pos);
// on a linear axis forces in N, positions in mm, M_acc as a mass in kg.
fit::Unit presentation(std::string_view name, fit::Axis axis = fit::Axis::Rotary);

}  // namespace knoblab::cli
