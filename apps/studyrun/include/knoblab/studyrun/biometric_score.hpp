// The thesis' biometric scores (§4.4.1.3), computed instead of read off by an
// expert: facial EMG valence as the smoothed corrugator − depressor trace's
// peak minus its baseline (signed: positive is positive valence), skin
// conductance arousal as its peak minus baseline. The baseline is the mean
// over the quiet time before the stimulus onset; the peak is looked for from
// onset to the trial's end. SI: V and S.
#pragma once

#include <optional>
#include <span>

#include <nlohmann/json.hpp>

#include "knoblab/store/types.hpp"

namespace knoblab::studyrun {

struct BiometricScore {
  std::optional<double> emg_V;  // none without samples in both windows
  std::optional<double> sc_S;
  std::size_t baseline_samples = 0, trial_samples = 0;
};

// EMG is rectified and smoothed by a moving RMS of `emg_window_s` per
// channel before the difference is taken (the raw signal is zero-mean).
BiometricScore score_biometrics(std::span<const store::BiometricSample> samples, double onset_s, double end_s,
                                double baseline_s, double emg_window_s = 0.25);

nlohmann::json to_json(const BiometricScore& score);

}  // namespace knoblab::studyrun
