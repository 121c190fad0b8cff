#include "knoblab/modbus/sim_signals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace knoblab::modbus::sim {
namespace {

constexpr double kMicro = 1e-6;

// EMG band-pass at fs = 32 Hz: AR(2) resonator around 8 Hz, scaled to unit
// variance so the envelope is the rms.
constexpr double kPoleRadius = 0.7;
const double kA1 = 2.0 * kPoleRadius * std::cos(2.0 * std::numbers::pi * 8.0 / 32.0);
constexpr double kA2 = -kPoleRadius * kPoleRadius;
double unit_gain() {
  const double var = (1.0 - kA2) / ((1.0 + kA2) * ((1.0 - kA2) * (1.0 - kA2) - kA1 * kA1));
  return 1.0 / std::sqrt(var);
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

double exponential(std::mt19937_64& rng, double mean) {
  return std::exponential_distribution<double>(1.0 / mean)(rng);
}

// Bi-exponential SCR shape, normalised to a peak of 1.
constexpr double kTauRise = 0.75, kTauDecay = 2.0;
double scr_shape(double dt) {
  if (dt <= 0.0) return 0.0;
  const double peak_t = std::log(kTauDecay / kTauRise) * kTauRise * kTauDecay / (kTauDecay - kTauRise);
  const double peak = std::exp(-peak_t / kTauDecay) - std::exp(-peak_t / kTauRise);
  return (std::exp(-dt / kTauDecay) - std::exp(-dt / kTauRise)) / peak;
}

}  // namespace

EmgChannel::EmgChannel(std::uint64_t seed, double rest_rms)
    : rng_(seed), rest_rms_(rest_rms), envelope_(rest_rms) {}

void EmgChannel::burst(double at, double length, double rms) {
  bursts_.push_back({at, at + length, rms});
}

double EmgChannel::step(double dt) {
  t_ += dt;
  double target = rest_rms_;
  for (const Burst& b : bursts_) {
    if (t_ >= b.start && t_ < b.end) target = std::max(target, b.rms);
  }
  std::erase_if(bursts_, [this](const Burst& b) { return b.end < t_; });
  // Muscle activity rises and falls over ~0.1 s, not sample to sample.
  envelope_ += (target - envelope_) * (1.0 - std::exp(-dt / 0.1));
  const double w = std::normal_distribution<double>(0.0, 1.0)(rng_);
  const double y = kA1 * y1_ + kA2 * y2_ + unit_gain() * w;
  y2_ = y1_;
  y1_ = y;
  return envelope_ * y;
}

BiometricsModel::BiometricsModel(std::uint64_t seed, Params params)
    : params_(params),
      rng_(seed),
      tonic_rng_(seed * 7 + 3),
      corrugator_(seed * 3 + 1, 2.0 * kMicro),
      depressor_(seed * 5 + 2, 1.5 * kMicro) {
  tonic_mean_ = uniform(rng_, 2.0, 8.0) * kMicro;
  tonic_ = tonic_mean_;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  next_stimulus_ = params_.trial_interval_max > 0.0 ? uniform(rng_, 3.0, 6.0) : kNever;
  next_spontaneous_ = params_.spontaneous_scr_interval > 0.0
                          ? exponential(rng_, params_.spontaneous_scr_interval) : kNever;
  next_burst_ = params_.random_burst_interval > 0.0 ? exponential(rng_, params_.random_burst_interval) : kNever;
}

void BiometricsModel::stimulus(double t) {
  // SCR: latency 2–3 s, amplitude 0.2–1 µS.
  scrs_.push_back({t + uniform(rng_, 2.0, 3.0), uniform(rng_, 0.2, 1.0) * kMicro});
  // Facial EMG: within a second, one muscle or the other.
  const double at = t + uniform(rng_, 0.3, 0.6);
  const double length = uniform(rng_, 0.8, 2.0);
  const double rms = uniform(rng_, 20.0, 60.0) * kMicro;
  if (uniform(rng_, 0.0, 1.0) < 0.5) {
    corrugator_.burst(at, length, rms);  // frown
  } else {
    depressor_.burst(at, length, rms);
  }
}

void BiometricsModel::sample(double t, double& emg_corrugator, double& emg_depressor,
                             double& skin_conductance) {
  const double dt = std::max(0.0, t - last_t_);
  last_t_ = t;
  // A trial every 8–14 s (the thesis' participants stroke a texture 3–5 s).
  while (t >= next_stimulus_) {
    stimulus(next_stimulus_);
    next_stimulus_ += uniform(rng_, params_.trial_interval_min, params_.trial_interval_max);
  }
  while (t >= next_spontaneous_) {
    scrs_.push_back({next_spontaneous_, uniform(rng_, 0.05, 0.2) * kMicro});
    next_spontaneous_ += exponential(rng_, params_.spontaneous_scr_interval);
  }
  while (t >= next_burst_) {
    EmgChannel& ch = uniform(rng_, 0.0, 1.0) < 0.5 ? corrugator_ : depressor_;
    ch.burst(next_burst_, uniform(rng_, 0.3, 1.0), uniform(rng_, 8.0, 30.0) * kMicro);
    next_burst_ += exponential(rng_, params_.random_burst_interval);
  }
  emg_corrugator = corrugator_.step(dt);
  emg_depressor = depressor_.step(dt);

  // Tonic level: mean-reverting drift over minutes.
  const double drift = std::normal_distribution<double>(0.0, 0.02 * kMicro * std::sqrt(dt))(tonic_rng_);
  tonic_ = std::max(0.5 * kMicro, tonic_ + (tonic_mean_ - tonic_) * dt / 60.0 + drift);
  double phasic = 0.0;
  for (const Scr& r : scrs_) phasic += r.amplitude * scr_shape(t - r.onset);
  std::erase_if(scrs_, [t](const Scr& r) { return t - r.onset > 30.0; });
  skin_conductance = tonic_ + phasic;
}

AmplifierModel::AmplifierModel(std::uint64_t seed) : rng_(seed) {
  s_.temperature = uniform(rng_, 26.0, 30.0);
}

const AmplifierState& AmplifierModel::step(double t, double dt, bool enabled, double limit) {
  constexpr double kAmbient = 28.0;   // °C
  constexpr double kHeating = 1.5;    // °C per A² at equilibrium
  constexpr double kThermalTau = 300; // s
  s_.enabled = enabled;
  // A knob being turned by hand: a slowly wandering load current.
  load_ += (std::normal_distribution<double>(0.0, 1.0)(rng_) - load_) * std::min(1.0, dt / 0.5);
  const double wanted = enabled ? 0.8 * std::sin(2.0 * std::numbers::pi * 0.7 * t) + 0.4 * load_ : 0.0;
  s_.current = std::clamp(wanted, -limit, limit);
  s_.limiting = enabled && std::abs(wanted) > limit;
  const double ripple = 0.15 * std::sin(2.0 * std::numbers::pi * 0.5 * t) +
                        std::normal_distribution<double>(0.0, 0.03)(rng_);
  s_.bus_voltage = 48.0 + ripple - 0.05 * std::abs(s_.current);
  const double equilibrium = kAmbient + kHeating * s_.current * s_.current;
  s_.temperature += (equilibrium - s_.temperature) * (1.0 - std::exp(-dt / kThermalTau)) +
                    std::normal_distribution<double>(0.0, 0.002)(rng_);
  return s_;
}

}  // namespace knoblab::modbus::sim
