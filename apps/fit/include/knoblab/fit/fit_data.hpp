// What the fitter fits: time series of the knob's motion and torque, SI
// units, prepared from a capture the way thesis §2.2.2.2 prepares it.
//
// Preparation (prepare()):
//  * Irregular time stamps (more than 1 % of intervals off the median by
//    over 10 %: a host PC's clock) are linearly interpolated onto the
//    median interval first, so filters and differences see one rate.
//  * 3rd-order Chebyshev II low-pass, 20 dB stop band, edges of Table 6
//    (θ, θ̇ 1000 Hz; θ̈, τ 500 Hz), run forward and backward (zero phase).
//    A channel whose edge is at or above 0.9·Nyquist is left unfiltered.
//  * θ̇ is the zero-phase derivative of the filtered θ: the recorded ω is the
//    loop's causal estimate, which lags. θ̈ is the calibrated accelerometer
//    (AlphaSource::Accelerometer, the default, as the thesis did) or the
//    derivative of θ̇ (Encoder). The accelerometer rides on the knob side of
//    the gripper, like the torque sensor's load, while the encoder is on the
//    motor: through a compliant gripper the motor's acceleration at a
//    breakaway is not the knob's, and M fitted on it comes out high (12 % on
//    the simulated high-friction knob).
//  * Samples the loop flagged (e-stop, fault latched, torque clipped) are
//    filtered with the rest, then left out of the fit.
//  * The axis (axis_units.hpp) is the capture's metadata's (capture_axis),
//    or PrepOptions::axis: a linear actuator's channels are m, m/s, N.
// The thesis also sorts by position before filtering; filtering in time
// keeps the filter meaningful, and the fit needs no order.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "knoblab/fit/axis_units.hpp"
#include "knoblab/interchange/capture.hpp"
#include "knoblab/interchange/sample.hpp"
#include "knoblab/model/terms.hpp"

namespace knoblab::fit {

// Thrown for data a fit cannot use (too short, no motion, bad sample times).
class FitDataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FitData {
  std::vector<double> t;      // s
  std::vector<double> theta;  // rad
  std::vector<double> omega;  // rad/s
  std::vector<double> alpha;  // rad/s²
  std::vector<double> torque; // N·m
  // The torque as recorded, before the low-pass (empty when not kept): a
  // sensor's clipping is a flat top here and ringing after the filter.
  std::vector<double> torque_recorded;  // N·m
  double rate_hz = 0.0;       // sample rate the preparation assumed
  bool resampled = false;     // irregular time stamps, interpolated onto 1/rate_hz
  bool alpha_from_encoder = false;  // α is the encoder's second derivative, not an accelerometer's
  // Linear: θ is a position in m, ω m/s, α m/s², the torque a force in N.
  // Nothing inside changes; the presentation does (axis_units.hpp).
  Axis axis = Axis::Rotary;
  // The low-pass the torque went through (Table 6; order 0: none): a model
  // that predicts the torque by simulation is filtered the same way before
  // it is compared, or a sharp transient's ring would count as its error.
  struct Lowpass {
    int order = 0;
    double stop_atten_db = 0.0, edge_hz = 0.0;
  } torque_lowpass;

  std::size_t size() const { return t.size(); }
  model::Kinematics<double> kinematics(std::size_t i) const {
    return {theta[i], omega[i], alpha[i]};
  }
};

enum class AlphaSource {
  Accelerometer,  // the recorded α column (calibrated accelerometer)
  Encoder,        // second derivative of the encoder, zero phase
};

struct PrepOptions {
  bool filter = true;  // Table 6 Chebyshev II, zero phase
  int order = 3;
  double stop_atten_db = 20.0;
  double edge_theta_hz = 1000.0, edge_omega_hz = 1000.0;
  double edge_alpha_hz = 500.0, edge_torque_hz = 500.0;
  AlphaSource alpha = AlphaSource::Accelerometer;
  // Flags that exclude a sample from the fit.
  std::uint32_t exclude_flags = interchange::kEstopActive | interchange::kFaultLatched |
                                interchange::kTorqueLimited;
  // The axis when the capture's metadata does not say (knoblab fit
  // --linear); one that says otherwise is an error.
  std::optional<Axis> axis;
};

// The axis a capture's metadata names: its `axis` entry (a CSV's `# axis:`
// line) or, for a capture read from the store, the `axis` member of its
// `metadata` object; nothing when neither says. Throws FitDataError naming
// the value when it is neither "rotary" nor "linear".
std::optional<Axis> capture_axis(const interchange::Capture& capture);

// The capture's axis, or `given` when it says none; rotary when neither
// does. Throws FitDataError when the two disagree.
Axis resolve_axis(const interchange::Capture& capture, std::optional<Axis> given);

// A capture whose α column was derived (absent from its CSV) uses the
// encoder whatever `opt.alpha` says. Throws FitDataError for an axis as
// resolve_axis does, for fewer than 100
// samples, non-increasing or non-finite times or values, or a knob that did
// not move.
FitData prepare(const interchange::Capture& capture, const PrepOptions& opt = {});

}  // namespace knoblab::fit
