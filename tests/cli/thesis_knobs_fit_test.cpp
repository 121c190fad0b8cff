// The five thesis knobs (Table 5), captured in
// simulation as `knoblab demo` captures them (Table 3 sweep through the PID,
// 5 s at 5 kHz) and fitted with no starting values, over several noise seeds.
//  * detents per revolution within 3 % of the gold standard (Tables 8/14) for
//    the knobs with detents, and no detent term for the two without;
//  * the Eq. 6 parameters inside their 95 % intervals in most (seed,
//    parameter) pairs for the four knobs Eq. 6 can describe. The non-sine
//    knob's detents have harmonics Eq. 6 lacks (thesis §2.2.2.4): only its
//    detent count is checked here; finding what is missing is discrepancy's
//    job.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "fit_run.hpp"
#include "knoblab/sim/presets.hpp"
#include "simulation.hpp"

namespace knoblab::cli {
namespace {

struct Knob {
  const char* id;
  int per_rev;          // gold standard; 0 = no detents
  bool eq6_describes;   // Eq. 6 is the simulated knob's whole model
};
constexpr Knob kKnobs[] = {{"high-friction", 0, true},
                           {"high-inertia", 0, true},
                           {"subtle-detents", 30, true},
                           {"moderate-detents", 12, true},
                           {"non-sine-detents", 12, false}};
constexpr int kSeeds = 4;

// The simulated knob's Eq. 6 vector in the fit's canonical spelling
// (A ≥ 0, S in (−π, π]).
std::vector<double> truth_of(const sim::KnobParams& k) {
  double A = k.detents.A, S = k.detents.S;
  if (A < 0) A = -A, S += std::numbers::pi;
  S = std::remainder(S, 2 * std::numbers::pi);
  return {k.inertia.M, k.friction.C_neg, k.friction.B_neg, k.friction.C_pos,
          k.friction.B_pos, A, k.detents.P, S};
}

TEST(ThesisKnobs, FittedAcrossSeedsDetentCountsAndIntervals) {
  std::printf("%-17s %5s %10s %9s  %s\n", "knob", "seed", "per rev", "covered", "misses");
  for (const Knob& k : kKnobs) {
    int covered = 0, pairs = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      SimulationRequest req;
      req.knob_name = k.id;
      req.knob = *sim::presets::knob(k.id);
      req.seed = static_cast<std::uint64_t>(seed);
      const SimulationResult s = simulate(req, nullptr);
      const fit::FitResult r = fit_capture(s.capture, {}, {}).result;

      const double per_rev = r.detents ? 1.0 / r.value("P_pos") : 0.0;
      if (k.per_rev == 0) {
        EXPECT_FALSE(r.detents) << k.id << " seed " << seed << ": spurious detents, "
                                << per_rev << " per rev";
      } else {
        ASSERT_TRUE(r.detents) << k.id << " seed " << seed;
        EXPECT_NEAR(per_rev, k.per_rev, 0.03 * k.per_rev) << k.id << " seed " << seed;
      }

      std::string misses;
      const std::vector<double> truth = truth_of(req.knob);
      for (std::size_t p = 0; p < truth.size(); ++p) {
        if (!r.fitted[p]) continue;  // no detent term: A, P, S held
        const bool in = r.ci95[p][0] <= truth[p] && truth[p] <= r.ci95[p][1];
        covered += in ? 1 : 0;
        ++pairs;
        if (!in) misses += " " + std::string(r.names[p]);
      }
      std::printf("%-17s %5d %10.2f %9s %s\n", k.id, seed, per_rev, "", misses.c_str());
    }
    const double share = static_cast<double>(covered) / pairs;
    std::printf("%-17s  %d of %d (seed, parameter) pairs inside their 95%% CI (%.0f %%)\n", k.id,
                covered, pairs, 100 * share);
    // Measured 80–84 %; the usual miss is M_acc, 3–7 % low: the accelerometer's
    // noise attenuates the regression on it (errors in variables).
    if (k.eq6_describes) {
      EXPECT_GE(share, 0.7) << k.id;
    }
  }
}

}  // namespace
}  // namespace knoblab::cli
