// A synthetic pointing study's tidy table, deterministic, shaped like the
// thesis' Study 3: 7 renderings × 2 amplitudes × 2 widths, a practice block
// and analysed blocks, 3 acquisitions a trial, each rendering with its own
// effect on movement time, end-point spread and rating, and biometrics
// that follow the rating.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "knoblab/study/tidy.hpp"

namespace knoblab::study::test {

inline const std::vector<std::string>& study3_renderings() {
  static const std::vector<std::string> names = {"not-rendered", "low-friction", "high-friction", "low-inertia",
                                                 "high-inertia", "few-detents",  "many-detents"};
  return names;
}

struct SyntheticPointing {
  unsigned participants = 12;
  unsigned analysed_blocks = 3;  // after one practice block
  unsigned seed = 3;
  bool biometrics = true;
  // A participant more, P99, who never did the last rendering: in the
  // trial-level statistics, not in the ANOVA and the rating tests.
  bool incomplete_participant = false;
};

inline std::vector<PointingRow> synthetic_pointing(const SyntheticPointing& s = {}) {
  const auto& renderings = study3_renderings();
  // Per rendering: movement-time factor, end-point spread factor, rating shift.
  const double mt_factor[] = {1.0, 0.97, 1.14, 0.91, 0.95, 1.06, 1.2};
  const double spread[] = {1.0, 0.9, 0.8, 1.0, 1.25, 0.85, 0.7};
  const double rating_shift[] = {0.0, 0.3, -1.4, 0.6, -0.7, 0.1, -2.1};
  const double amplitudes[] = {30.0, 200.0}, widths[] = {1.4, 11.3};
  std::mt19937 rng(s.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<PointingRow> rows;
  const unsigned people = s.participants + (s.incomplete_participant ? 1 : 0);
  for (unsigned p = 0; p < people; ++p) {
    const bool incomplete = p == s.participants;
    char code[16];
    std::snprintf(code, sizeof code, "P%02u", incomplete ? 99u : p + 1);
    const double speed = std::exp(0.2 * normal(rng));
    const double leniency = 0.8 * normal(rng);
    const bool no_biometrics = !s.biometrics || p == 2;  // one participant's sensors never worked
    unsigned trial = 0;
    for (unsigned block = 1; block <= 1 + s.analysed_blocks; ++block) {
      const bool practice = block == 1;
      for (std::size_t j = 0; j < renderings.size(); ++j) {
        if (incomplete && j + 1 == renderings.size()) continue;
        for (const double a : amplitudes) {
          for (const double w : widths) {
            ++trial;
            const double id = std::log2(a / w + 1);
            int direction = uniform(rng) < 0.5 ? 1 : -1;
            const double rating_value = 5 + rating_shift[j] + leniency + 0.3 * (w > 5 ? 1 : -1) + 1.2 * normal(rng);
            const int rating = static_cast<int>(std::clamp(std::round(rating_value), 1.0, 9.0));
            for (unsigned acquisition = 1; acquisition <= 3; ++acquisition) {
              PointingRow r;
              r.participant = code;
              r.session = 1;
              r.block = block;
              r.trial = trial;
              r.practice = practice;
              r.stage = "all";
              r.rendering = renderings[j];
              r.amplitude_deg = a;
              r.width_deg = w;
              r.acquisition = acquisition;
              r.direction = direction;
              direction = -direction;
              // Practice is slow and wild: leaving it out must show.
              r.movement_time_s = (practice ? 3.0 : 1.0) * speed * mt_factor[j] * (0.25 + 0.16 * id) *
                                  std::exp(0.18 * normal(rng));
              r.endpoint_deg = 0.05 * w + spread[j] * (w / 4.133) * (0.7 + 0.02 * a / 30) * normal(rng);
              r.overshoot_deg = std::max(0.0, r.endpoint_deg + std::abs(0.3 * w * normal(rng)) - w / 2);
              r.rating = rating;
              if (!no_biometrics && uniform(rng) > 0.05) {
                r.emg_uV = 4 + 0.35 * rating + 0.8 * normal(rng);
                r.sc_uS = 2 + 0.1 * normal(rng) + 0.02 * rating;
              }
              rows.push_back(r);
            }
          }
        }
      }
    }
  }
  return rows;
}

}  // namespace knoblab::study::test
