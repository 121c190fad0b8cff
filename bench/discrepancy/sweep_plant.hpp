// The plants the effect-size sweep captures from (README.md, "The effect-size
// sweep"): knoblab's simulator and the independently written two-body rig,
// each carrying the same effects in its own way, and the knobs both take.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "knoblab/interchange/capture.hpp"
#include "knoblab/sim/knob.hpp"

namespace knoblab::bench {

// One concealed effect as a plant carries it: the effect discovery should
// name, and the one setting the sweep varies to size it.
struct SweepEffect {
  std::string id;       // discovery's name for it
  std::string setting;  // what is varied, named with its unit
  double lo = 0.0, hi = 0.0;  // the setting's range (lo > 0: sized on a log scale)
  double start = 0.0;         // the first setting tried
  // Position-only torques go on knobs with detents: on one without, Eq. 6's
  // detent term (0.5–200 cycles/rev) takes them up whole, which is the
  // thesis model describing the data, not a discrepancy.
  bool needs_detents = false;
  bool grows_with_setting = true;  // false: the effect grows as the setting falls (a softer coupling)
};

// The second periodic torque both benchmarks conceal: 17.3 cycles/rev, away
// from the thesis knobs' 12 and 30 detents and their harmonics.
inline constexpr double kCoggingPeriodRad = 2.0 * 3.14159265358979323846 * 0.0578;

// A knob both plants take, by its parameter values (SI).
struct SweepKnob {
  std::string name;
  sim::KnobParams params;
  std::string truth = "none";  // what it has beyond Eq. 6 by itself
  bool detents() const { return params.detents.A != 0.0; }
};

// The thesis knobs (Table 7 set 1, as sim/presets.hpp reads them) and the
// spring-return knob; quick: moderate-detents and the spring-return knob.
std::vector<SweepKnob> sweep_knobs(bool quick);

class SweepPlant {
 public:
  virtual ~SweepPlant() = default;
  virtual std::string name() const = 0;
  virtual std::vector<SweepEffect> effects() const = 0;
  // An 8 s, 5 kHz capture of `knob`, clean when `effect` is null. The same
  // seed gives the same noise with and without the effect.
  virtual interchange::Capture capture(const SweepKnob& knob, const SweepEffect* effect, double setting,
                                       std::uint64_t seed) const = 0;
  // What the capture carries, as knoblab simulate --effects would say it.
  virtual std::string describe(const SweepEffect& effect, double setting) const = 0;
  // The torque channel's own noise, N·m RMS (NaN: not one figure).
  virtual double torque_noise() const = 0;
};

std::unique_ptr<SweepPlant> sim_sweep_plant();
// α from the motor encoder, or from a knob-side accelerometer.
std::unique_ptr<SweepPlant> two_body_sweep_plant(bool accelerometer);

}  // namespace knoblab::bench
