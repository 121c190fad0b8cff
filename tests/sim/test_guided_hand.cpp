// The guided hand a simulated participant steers: it takes hold where the
// knob is, carries it along minimum-jerk reaches, and shrugs off commands a
// broken writer could send.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "knoblab/sim/guided_hand.hpp"
#include "knoblab/sim/plant.hpp"
#include "knoblab/sim/presets.hpp"

namespace knoblab::sim {
namespace {

struct HandOnKnob {
  HandChannel channel;
  Plant plant{config()};
  HandOnKnob() { plant.add_effect(make_guided_hand(channel)); }
  static PlantConfig config() {
    PlantConfig c;
    c.knob = presets::find("study3-not-rendered")->knob;
    c.initial_angle = 0.3;
    return c;
  }
  void run(double seconds) {
    for (double t = 0; t < seconds; t += 1e-3) plant.step(0.0, 1e-3);
  }
  double angle() const { return plant.state().knob_angle; }
};

TEST(GuidedHand, TakesHoldWhereTheKnobIsAndCarriesItToTheReachsEnd) {
  HandOnKnob h;
  h.run(0.1);
  EXPECT_NEAR(h.angle(), 0.3, 1e-9) << "no command yet: the hand is off the knob";
  h.channel.send({1.3, 0.5, 1.0, 0.01});
  h.plant.step(0.0, 1e-3);
  EXPECT_NEAR(h.angle(), 0.3, 1e-3) << "no jump when the hand takes hold";
  h.run(0.25);
  // Halfway through a minimum-jerk reach the hand is halfway there.
  EXPECT_NEAR(h.angle(), 0.8, 0.05);
  h.run(0.6);
  EXPECT_NEAR(h.angle(), 1.3, 0.01);
}

TEST(GuidedHand, StartsANewReachFromWhereTheOldOneHadGotTo) {
  HandOnKnob h;
  h.channel.send({1.3, 1.0, 1.0, 0.01});
  h.run(0.5);  // halfway: 0.8
  const double there = h.angle();
  h.channel.send({-0.2, 0.5, 1.0, 0.01});
  h.run(0.01);
  EXPECT_NEAR(h.angle(), there, 0.02) << "the hand turns back smoothly, no step";
  h.run(1.0);
  EXPECT_NEAR(h.angle(), -0.2, 0.01);
}

TEST(GuidedHand, IgnoresCommandsOutsideItsBoundsOrNotFinite) {
  HandOnKnob h;
  h.channel.send({0.5, 0.2, 1.0, 0.01});
  h.run(0.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const HandCommand bad : {HandCommand{nan, 0.2, 1, 0.01}, HandCommand{5, -1, 1, 0.01},
                                HandCommand{5, 0.2, 1e9, 0.01}, HandCommand{5, 0.2, 1, -1},
                                HandCommand{1e6, 0.2, 1, 0.01}}) {
    EXPECT_FALSE(valid(bad));
    h.channel.send(bad);
    h.run(0.3);
    EXPECT_NEAR(h.angle(), 0.5, 0.01);
    EXPECT_TRUE(std::isfinite(h.angle()));
  }
}

TEST(GuidedHand, LetsGoWhenTheGripIsZero) {
  HandOnKnob h;
  h.channel.send({0.5, 0.2, 1.0, 0.01});
  h.run(0.5);
  h.channel.send({2.0, 0.2, 0.0, 0.0});
  h.run(0.5);
  EXPECT_NEAR(h.angle(), 0.5, 0.01) << "a hand off the knob moves nothing";
}

TEST(GuidedHand, ChannelDeliversEachCommandOnceAndTheNewestOnly) {
  HandChannel c;
  std::uint64_t seen = 0;
  HandCommand out;
  EXPECT_FALSE(c.receive(seen, out));
  c.send({1, 0.1, 1, 0});
  c.send({2, 0.1, 1, 0});
  ASSERT_TRUE(c.receive(seen, out));
  EXPECT_EQ(out.target_rad, 2);
  EXPECT_FALSE(c.receive(seen, out));
}

TEST(GuidedHand, MinimumJerkStartsAndEndsAtRest) {
  EXPECT_DOUBLE_EQ(minimum_jerk(0, 1, 0.5, 0).omega, 0.0);
  EXPECT_DOUBLE_EQ(minimum_jerk(0, 1, 0.5, 0.5).theta, 1.0);
  EXPECT_NEAR(minimum_jerk(0, 1, 0.5, 0.25).theta, 0.5, 1e-12);
  EXPECT_NEAR(minimum_jerk(0, 1, 0.5, 0.25).omega, 1.875 / 0.5, 1e-12);  // peak speed 1.875·D/T
}

}  // namespace
}  // namespace knoblab::sim
