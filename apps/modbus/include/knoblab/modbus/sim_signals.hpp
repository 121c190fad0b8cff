// Plausible device signals for the simulator, in SI units, deterministic
// for a seed. Used by SimServer; public so tests can check the timings.
//
// Biometrics (thesis §4.4.1.2; timings from the psychophysiology literature):
// * EMG (corrugator, depressor supercilii): zero-mean band-limited noise at a
//   resting ~2 µV rms whose envelope rises to tens of µV in bursts, now and
//   then at random and 0.3–0.6 s after a stimulus (a frown on the corrugator,
//   the opposite expression on the depressor: the thesis' valence is their
//   difference).
// * Skin conductance: a tonic level of a few µS drifting slowly, plus phasic
//   responses (SCRs) that start 2–3 s after a stimulus, rise in ~1 s and
//   recover over several seconds (bi-exponential, τ 0.75 s / 2 s), and a few
//   spontaneous ones.
// Amplifier: bus ~48 V with ripple and load sag, a first-order thermal model,
// a load current while enabled, clamped to the current limit.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace knoblab::modbus::sim {

class EmgChannel {
 public:
  EmgChannel(std::uint64_t seed, double rest_rms);
  double step(double dt);                // one sample, V
  void burst(double at, double length, double rms);  // schedule one (times in s)

 private:
  std::mt19937_64 rng_;
  double rest_rms_;
  double y1_ = 0.0, y2_ = 0.0;  // AR(2) band-pass state
  double envelope_;
  double t_ = 0.0;
  struct Burst { double start, end, rms; };
  std::vector<Burst> bursts_;
};

class BiometricsModel {
 public:
  struct Params {
    double trial_interval_min = 8.0;   // s between automatic stimuli (a trial)…
    double trial_interval_max = 14.0;  // … 0/0: no automatic stimuli
    double spontaneous_scr_interval = 20.0;  // s, mean; 0: none
    double random_burst_interval = 8.0;      // s, mean EMG burst interval; 0: none
  };
  explicit BiometricsModel(std::uint64_t seed) : BiometricsModel(seed, Params{}) {}
  BiometricsModel(std::uint64_t seed, Params params);
  // Advance to time t (s since start) by one 32 Hz sample.
  void sample(double t, double& emg_corrugator, double& emg_depressor, double& skin_conductance);
  void stimulus(double t);  // a stimulus presented at t

 private:
  struct Scr { double onset, amplitude; };
  Params params_;
  std::mt19937_64 rng_;
  std::mt19937_64 tonic_rng_;  // own stream: a stimulus must not change the tonic level
  EmgChannel corrugator_, depressor_;
  double tonic_, tonic_mean_;
  std::vector<Scr> scrs_;
  double last_t_ = 0.0;
  double next_stimulus_, next_spontaneous_, next_burst_;
};

struct AmplifierState {
  bool enabled = false;
  bool limiting = false;
  double bus_voltage = 48.0;  // V
  double temperature = 28.0;  // °C
  double current = 0.0;       // A
};

class AmplifierModel {
 public:
  explicit AmplifierModel(std::uint64_t seed);
  // Advance by dt at time t; enabled: output stage on; limit: A.
  const AmplifierState& step(double t, double dt, bool enabled, double limit);

 private:
  std::mt19937_64 rng_;
  AmplifierState s_;
  double load_ = 0.0;  // smoothed random load, A
};

}  // namespace knoblab::modbus::sim
