// step() runs in the 10 kHz realtime loop: it must never allocate. Count
// every global operator new while a flag is up.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"
#include "alloc_counter.hpp"

using knoblab::test::g_allocations;
using knoblab::test::g_counting;

using namespace knoblab::sim;

namespace {
class Drag : public KnobEffect {
 public:
  double torque(const KnobMotion& k, double) const override { return 1e-4 * k.omega; }
};
}  // namespace

TEST(Realtime, CounterSeesAllocations) {
  g_allocations = 0;
  g_counting = true;
  auto p = std::make_unique<int>(3);
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 1);
}

TEST(Realtime, StepDoesNotAllocate) {
  for (const auto& preset : presets::all()) {
    for (AmpMode mode : {AmpMode::Current, AmpMode::Voltage}) {
      PlantConfig c;
      c.knob = preset.knob;
      c.amp.mode = mode;
      Plant p(c);
      p.add_effect(std::make_unique<Drag>());
      g_allocations = 0;
      g_counting = true;
      for (int n = 0; n < 2000; ++n) p.step(6.0 * ((n / 500) % 2 ? -1.0 : 1.0), 1e-4);
      p.step(1.0, 1e-3);  // a slower tick: more substeps
      g_counting = false;
      EXPECT_EQ(g_allocations.load(), 0) << preset.id;
    }
  }
}

TEST(Realtime, StepWithRigEffectsDoesNotAllocate) {
  // The torque channel's delay line and the Dahl state live in the Plant.
  PlantConfig c;
  c.knob = *presets::knob("moderate-detents");
  c.knob.presliding = 0.002;
  c.torque_sensor.delay = 0.003;
  c.torque_sensor.saturation = 0.01;
  Plant p(c);
  g_allocations = 0;
  g_counting = true;
  for (int n = 0; n < 2000; ++n) p.step(6.0 * ((n / 500) % 2 ? -1.0 : 1.0), 1e-4);
  p.step(1.0, 1e-3);
  p.step(1.0, 1e-6);  // a tiny tick: substeps far under the delay line's grid
  p.reset();
  g_counting = false;
  EXPECT_EQ(g_allocations.load(), 0);
}
