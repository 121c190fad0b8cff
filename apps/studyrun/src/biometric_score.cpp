#include "knoblab/studyrun/biometric_score.hpp"

#include <cmath>
#include <vector>

namespace knoblab::studyrun {

BiometricScore score_biometrics(std::span<const store::BiometricSample> s, double onset_s, double end_s,
                                double baseline_s, double emg_window_s) {
  BiometricScore out;
  // Moving RMS of each EMG channel over the samples within emg_window_s before each one.
  std::vector<double> emg(s.size());
  double sum_c = 0, sum_d = 0;
  std::size_t first = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    sum_c += s[i].emg_corrugator * s[i].emg_corrugator;
    sum_d += s[i].emg_depressor * s[i].emg_depressor;
    while (s[first].t < s[i].t - emg_window_s) {
      sum_c -= s[first].emg_corrugator * s[first].emg_corrugator;
      sum_d -= s[first].emg_depressor * s[first].emg_depressor;
      ++first;
    }
    const double n = static_cast<double>(i - first + 1);
    emg[i] = std::sqrt(std::max(0.0, sum_c) / n) - std::sqrt(std::max(0.0, sum_d) / n);
  }
  double base_emg = 0, base_sc = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i].t >= onset_s - baseline_s && s[i].t < onset_s) {
      base_emg += emg[i];
      base_sc += s[i].skin_conductance;
      ++out.baseline_samples;
    }
  if (out.baseline_samples == 0) return out;
  base_emg /= static_cast<double>(out.baseline_samples);
  base_sc /= static_cast<double>(out.baseline_samples);
  double peak_emg = 0, peak_sc = -1e300;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i].t >= onset_s && s[i].t <= end_s) {
      if (out.trial_samples == 0 || std::abs(emg[i] - base_emg) > std::abs(peak_emg - base_emg)) peak_emg = emg[i];
      peak_sc = std::max(peak_sc, s[i].skin_conductance);
      ++out.trial_samples;
    }
  if (out.trial_samples == 0) return out;
  out.emg_V = peak_emg - base_emg;
  out.sc_S = peak_sc - base_sc;
  return out;
}

nlohmann::json to_json(const BiometricScore& b) {
  auto value = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"emg_V", value(b.emg_V)}, {"sc_S", value(b.sc_S)}, {"baseline_samples", b.baseline_samples},
          {"trial_samples", b.trial_samples}};
}

}  // namespace knoblab::studyrun
