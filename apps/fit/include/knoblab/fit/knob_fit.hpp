// Fitting a knob model to prepared data (thesis §2.1–2.2, Eq. 6 and 7) with
// Ceres, using the torque terms of the model core (autodiff).
//
//   FitData d = prepare(capture.samples);
//   FitResult r = fit_knob(d);            // thesis6, no starting values needed
//   r.value("P_pos"), r.ci95[...], r.rmse_Nm, r.stick
//
// How it avoids the thesis' sensitivity to initial conditions (§2.3):
//  1. With P fixed, Eq. 6 is linear in everything else (A·sin(θ/P + S) =
//     a·sin(θ/P) + b·cos(θ/P)). A linear fit of the friction and inertia
//     terms leaves the position-periodic residual; binned by position, its
//     angular periodogram over all detent counts the data can resolve gives P
//     (the global peak, so never a neighbouring period).
//  2. The peak must stand out of the periodogram's noise floor (false-alarm
//     probability < 1e-4) or the knob has no detents and the detent term is
//     left out (A = 0, P and S not fitted).
//  3. The detent start (A, S) is the periodogram's sinusoid at the peak, the
//     others come from step 1's linear fit; Levenberg–Marquardt then refines
//     all parameters jointly, over position cells (position_cells.hpp) unless
//     FitOptions::compress is off.
//  4. The Karnopp stick band (Eq. 7) is estimated from the friction residual
//     near zero velocity; samples inside it do not obey the sliding law, so
//     the fit is repeated without them.
//  5. Samples whose residual lies beyond five robust standard deviations
//     (breakaway transients, a compliant gripper ringing) are left out and
//     the fit is repeated once: a few such samples with large accelerations
//     would otherwise set M.
// Confidence intervals come from the parameter covariance. Residuals of real
// (and filtered) data are correlated, so the covariance is the sandwich
// estimate with batch means of the scores (64 contiguous batches) and the
// intervals use Student's t with 63 degrees of freedom; for white noise this
// matches the textbook σ²(JᵀJ)⁻¹.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/run_hooks.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::fit {

// The models a fit can use. Names are what the CLI and the JSON use.
enum class ModelKind {
  Thesis6,  // Eq. 6: M_acc, C_vel_neg, B_vel_neg, C_vel_pos, B_vel_pos, A_pos, P_pos, S_pos
  Render4,  // Eq. 14: M_acc, B_vel, A_pos, P_pos (+ S_pos, the capture's detent phase)
};
std::string_view model_name(ModelKind m);
std::optional<ModelKind> parse_model(std::string_view name);
// Parameter names in fit order.
std::vector<std::string_view> param_names(ModelKind m);

struct FitOptions {
  ModelKind model = ModelKind::Thesis6;
  // Detent search range, cycles per revolution. The lower end is raised to
  // half a cycle over the position range the capture covers.
  double min_detents_per_rev = 0.5;
  double max_detents_per_rev = 200.0;
  enum class Detents { Auto, Force, None } detents = Detents::Auto;
  bool stick_band = true;      // estimate Eq. 7's Δv, D−, D+
  bool trim_outliers = true;   // leave out residuals beyond 5 robust SDs (breakaway transients)
  // Iterate over position cells (position_cells.hpp: exact up to a detent
  // interpolation error ~1e-8·A) instead of every sample.
  bool compress = true;
  std::optional<std::vector<double>> start;  // skip the search; full parameter vector
  int max_iterations = 100;
  int threads = 2;
  // Progress ("searching detents", "fitting", "stick band", "outliers",
  // "intervals") and cancellation: fit_knob throws Cancelled.
  RunHooks hooks;
};

// Karnopp stick band (Eq. 7), SI units.
struct StickBand {
  double dv = 0.0;     // rad/s
  double D_neg = 0.0;  // N·m, magnitude
  double D_pos = 0.0;  // N·m
  std::size_t samples = 0;  // samples inside the band
};

// Where fit_knob's wall time went, seconds (the benchmark's breakdown).
struct FitPhases {
  double start = 0.0;       // moving samples, linear fit, detent search
  double cells = 0.0;       // building and factoring the position cells
  double solve = 0.0;       // Levenberg–Marquardt, all runs
  double stick_band = 0.0;  // Eq. 7 estimate and leaving the band out
  double trim = 0.0;        // robust scale and leaving outliers out
  double covariance = 0.0;  // covariance, intervals and summary figures
};

struct FitResult {
  ModelKind model = ModelKind::Thesis6;
  Axis axis = Axis::Rotary;               // the data's, for presentation (axis_units.hpp)
  std::vector<std::string_view> names;
  std::vector<double> params;             // SI, fit order
  std::vector<bool> fitted;               // false: held (no detents)
  std::vector<double> se;                 // standard errors (0 when held)
  std::vector<std::array<double, 2>> ci95;
  std::vector<double> covariance;         // row-major, names.size()²
  double t95 = 0.0;                       // the t quantile the intervals use

  bool detents = false;
  double detent_power = 0.0;       // explained share of the position residual at the peak
  double detent_false_alarm = 1.0; // probability of a peak that high from noise
  std::optional<StickBand> stick;

  std::size_t samples = 0;      // samples fitted (outside the stick band, not outliers)
  std::size_t outliers = 0;     // left out as beyond 5 robust SDs
  double rmse_Nm = 0.0;
  double fit_percent = 0.0;     // 100·(1 − ‖y − ŷ‖ / ‖y − ȳ‖), Matlab's "fit"
  double bic = 0.0;             // n·ln(RSS/n) + k·ln(n)
  double residual_sd = 0.0;     // √(RSS / (n − k))
  double ci95_torque_Nm = 0.0;  // mean half-width of the fitted-curve band (Table 7's last row)
  double covariance_inflation = 1.0;  // sandwich vs textbook variance, mean over parameters
  int iterations = 0;
  double seconds = 0.0;
  FitPhases phases;

  double value(std::string_view name) const;  // throws std::out_of_range
  std::size_t index(std::string_view name) const;
};

// Throws FitDataError when the data cannot identify the model, Cancelled
// when opt.hooks says so.
FitResult fit_knob(const FitData& data, const FitOptions& opt = {});

// The fitted Eq. 6 model (render4 maps onto it with C = 0, B− = B+ = B).
model::ThesisModel<double> thesis_model(const FitResult& r);

// Per-sample fitted torque, its parts and the 95% bands (Matlab's nlpredci):
// curve = the fitted mean torque's interval, observation = where a new
// measurement falls.
struct Prediction {
  std::vector<double> tau, acc, vel, pos;  // fitted τ and its Eq. 6 parts
  std::vector<double> curve_half, observation_half;
};
Prediction predict(const FitResult& r, const FitData& data);

}  // namespace knoblab::fit
