// The effect-size sweep (README.md, "The effect-size sweep"): on a plant, for
// each knob and each effect it carries, captures at effect/noise ratios from
// 0.5 to 30, and what discovery names in each; the clean knobs for false
// alarms.
//
// Effect size = RMS of the part of the effect's torque that the base model
// cannot take up, over the rows discovery analyses, ÷ r (absorption.hpp):
// the change in residual under the clean knob's Eq. 6 from the clean
// capture to this one (same knob and seed, so the sensor noise cancels),
// less its projection on Eq. 6's parameter sensitivities. A quadratic drag
// that is 98 % more viscous damping is a small discrepancy however large
// its torque; the whole change is kept beside it (`raw_rms_Nm`). The rows
// are those discovery analysed on the clean capture: faster than its
// fitted stick band and 2 % of the 95th-percentile speed. r is the clean
// capture's held-out residual RMS under the base model: the noise the
// effect is seen through, the sensor's and whatever of the clean knob Eq. 6
// does not describe (on the two-body rig, r is close to its torque noise;
// on the simulator the accelerometer's noise through M adds to it). The
// setting for a target ratio is found on a log–log secant over captures of
// the plant; cases are binned by the ratio they got.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "case_analysis.hpp"
#include "sweep_plant.hpp"

namespace knoblab::bench {

struct SweepCase {
  std::string plant, knob;
  std::string truth = "none";  // the concealed effect; a clean knob's own ("none", "spring")
  std::uint64_t seed = 1;
  std::string spec;            // what the capture carries
  double setting = 0.0;
  // Effect size asked for and got (NaN for a clean knob).
  double target = std::numeric_limits<double>::quiet_NaN();
  double ratio = std::numeric_limits<double>::quiet_NaN();
  // The effect's RMS that Eq. 6 cannot take up (absorption.hpp), which
  // sizes the case, and the whole of its torque change.
  double effect_rms_Nm = 0.0, raw_rms_Nm = 0.0, r_Nm = 0.0;
  Analysis analysis;
  std::string error;  // why the case has no analysis (a capture that failed)
  bool clean() const { return spec.empty(); }
};

struct SweepOptions {
  std::vector<double> targets;  // effect/noise ratios
  int seeds = 1;
  std::string only;             // one effect id; empty: every one
  std::string knob;             // one knob's name; empty: every one
  bool quick = false;
  // Each case's capture written there as CSV (knob-effect-target-seed.csv;
  // clean knobs as knob-clean-seed.csv), for knoblab discrepancy --input.
  std::string captures_dir;
};

// The targets: 0.5–30, fewer when quick.
std::vector<double> sweep_targets(bool quick);

// Runs the plant's sweep; `done` sees each case as it finishes.
void run_sweep(const SweepPlant& plant, const SweepOptions& opt, const std::function<void(const SweepCase&)>& done);

// Detection per effect against effect-size bins, false alarms on the clean
// knobs, the spring-return knob and the analysis times, for one plant.
void print_sweep_summary(const std::string& plant, double torque_noise, const std::vector<SweepCase>& cases);
nlohmann::json sweep_case_json(const SweepCase& c);
nlohmann::json sweep_summary_json(const std::vector<SweepCase>& cases);

}  // namespace knoblab::bench
