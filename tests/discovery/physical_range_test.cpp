// A name is a physical claim: a candidate fitted outside the range the effect
// table gives its parameters is not that effect, however much it explains.
#include <gtest/gtest.h>

#include <string>

#include "effect_data.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/model/effects.hpp"

namespace knoblab::discovery {
namespace {

bool named(const DiscrepancyResult& r, EffectId id) {
  for (const Finding& f : r.findings)
    if (f.effect == id) return true;
  for (const Finding& f : r.tentative)
    if (f.effect == id) return true;
  return false;
}

TEST(PhysicalRange, ADipInFrictionNearZeroSpeedIsNotNamedStribeck) {
  // Friction 3 N·m *below* its Coulomb level near zero speed: Stribeck's law
  // with a negative excess fits it, but static friction above kinetic is what
  // the name says.
  const fit::FitData d = test_data::with_effect(21, [](const fit::FitData& x, std::size_t i) {
    return model::Stribeck<double>{-3.0, 2.0}.torque(x.omega[i]);
  });
  DiscrepancyOptions opt;
  opt.min_reported_gain = 0.0;
  const DiscrepancyResult r = discover(d, opt);
  EXPECT_FALSE(named(r, EffectId::Stribeck)) << to_json(r);
  for (const CandidateScore& c : r.candidates) EXPECT_NE(c.effect, EffectId::Stribeck) << "scored: " << to_json(r);
}

TEST(PhysicalRange, StribeckAboveTheCoulombLevelIsStillNamed) {
  const fit::FitData d = test_data::with_effect(21, [](const fit::FitData& x, std::size_t i) {
    return model::Stribeck<double>{3.0, 2.0}.torque(x.omega[i]);
  });
  DiscrepancyOptions opt;
  opt.min_reported_gain = 0.0;
  const DiscrepancyResult r = discover(d, opt);
  EXPECT_TRUE(named(r, EffectId::Stribeck)) << to_json(r);
}

}  // namespace
}  // namespace knoblab::discovery
