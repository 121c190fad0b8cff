// The pointing task's measures on scripted knob movements: when a target
// counts as acquired, and where each movement ended.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "knoblab/study/protocol.hpp"
#include "knoblab/studyrun/pointing_task.hpp"
#include "protocols.hpp"

namespace knoblab::test {
namespace {

using studyrun::KnobReading;
using studyrun::Step;

constexpr double kDeg = std::numbers::pi / 180;

struct Script {
  explicit Script(studyrun::PointingTask made) : task(std::move(made)) {}
  studyrun::PointingTask task;
  double t = 0;
  double theta = 0;
  std::vector<Step> steps;
  // Moves the knob to `to` over `seconds` along a smooth (minimum-jerk)
  // path, feeding a reading every millisecond.
  void move(double to, double seconds) {
    const double from = theta;
    for (double s = 1e-3; s <= seconds + 1e-9; s += 1e-3) {
      const double u = s / seconds;
      const double shape = u * u * u * (10 - 15 * u + 6 * u * u);
      const double rate = 30 * u * u * (1 - 2 * u + u * u) / seconds;
      theta = from + (to - from) * shape;
      feed({t += 1e-3, theta, (to - from) * rate, 0});
    }
  }
  void hold(double seconds) {
    for (double s = 0; s < seconds; s += 1e-3) feed({t += 1e-3, theta, 0, 0});
  }
  void feed(const KnobReading& r) { steps.push_back(task.feed(r, {})); }
};

study::Trial trial_towards(int direction, double amplitude_deg, double width_deg) {
  study::Trial t;
  t.index = 1;
  t.levels = {0, 0, 0};
  for (unsigned k = 1; k <= 3; ++k)
    t.targets.push_back({k, k % 2 == 1 ? direction * amplitude_deg * kDeg : 0.0, width_deg * kDeg,
                         k % 2 == 1 ? direction : -direction});
  return t;
}

TEST(PointingTask, StartsOnlyOnceTheNeedleRestsOnTheHomeDiskAndThenRendersTheCondition) {
  const study::Protocol p = shortened_pointing();
  Script s(studyrun::PointingTask(p, trial_towards(1, 30, 11.3)));
  s.theta = 5 * kDeg;  // off the 1.4° home disk
  s.hold(1.0);
  EXPECT_EQ(std::count(s.steps.begin(), s.steps.end(), Step::Onset), 0);
  EXPECT_FALSE(s.task.rendering_change());
  s.move(0.2 * kDeg, 0.4);
  s.hold(0.35);
  ASSERT_EQ(std::count(s.steps.begin(), s.steps.end(), Step::Onset), 1);
  EXPECT_TRUE(s.task.rendering_change());
  EXPECT_FALSE(s.task.rendering_change()) << "the rendering is asked for once";
  ASSERT_TRUE(s.task.display().disk);
  EXPECT_NEAR(s.task.display().disk->centre_rad, 30 * kDeg, 1e-12);
}

TEST(PointingTask, MeasuresMovementTimeEndPointAndOvershootOfEachAcquisition) {
  const study::Protocol p = shortened_pointing();
  Script s(studyrun::PointingTask(p, trial_towards(-1, 30, 11.3)));
  s.hold(0.31);  // on the home disk already: onset after 0.3 s at rest
  ASSERT_EQ(std::count(s.steps.begin(), s.steps.end(), Step::Onset), 1);
  // Out to −34° (4° past the −30° centre, inside the 11.3° disk), back to
  // +3°, out to −40° (past the far edge at −35.65°: an overshoot).
  s.hold(0.2);
  s.move(-34 * kDeg, 0.5);
  s.move(3 * kDeg, 0.5);
  s.move(-40 * kDeg, 0.5);
  s.hold(0.1);
  ASSERT_EQ(s.steps.back(), Step::Done);
  const nlohmann::json r = s.task.result();
  ASSERT_EQ(r["acquisitions"].size(), 3u);
  const auto& a1 = r["acquisitions"][0];
  const auto& a2 = r["acquisitions"][1];
  const auto& a3 = r["acquisitions"][2];
  EXPECT_EQ(a1["direction"], -1);
  EXPECT_NEAR(a1["endpoint_deg"].get<double>(), 4.0, 0.05);  // ends as it comes to rest
  EXPECT_DOUBLE_EQ(a1["overshoot_deg"].get<double>(), 0.0);
  EXPECT_NEAR(a2["endpoint_deg"].get<double>(), 3.0, 0.05);  // back past home by 3°
  EXPECT_NEAR(a3["endpoint_deg"].get<double>(), 10.0, 0.05);
  EXPECT_NEAR(a3["overshoot_deg"].get<double>(), 10.0 - 11.3 / 2, 0.05);
  EXPECT_NEAR(a1["amplitude_deg"].get<double>(), 30.0, 1e-9);
  EXPECT_NEAR(a2["amplitude_deg"].get<double>(), 30.0, 1e-9);
  // Shown at onset (0.301 s); entered (its near edge at −24.35°) after the
  // rest of the hold, the 0.2 s wait and most of the first movement.
  EXPECT_NEAR(r["onset_s"].get<double>(), 0.301, 1.5e-3);
  const double mt1 = a1["movement_time_s"].get<double>();
  EXPECT_GT(mt1, 0.009 + 0.2 + 0.25);
  EXPECT_LT(mt1, 0.009 + 0.2 + 0.5);
  EXPECT_FALSE(r["timed_out"].get<bool>());
}

TEST(PointingTask, EndsATrialWhoseTargetIsNeverReachedAsTimedOutWithoutInventingMeasures) {
  const study::Protocol p = shortened_pointing();
  studyrun::PointingTiming timing;
  timing.acquisition_timeout_s = 2;
  Script s(studyrun::PointingTask(p, trial_towards(1, 200, 1.4), timing));
  s.hold(0.31);
  s.move(100 * kDeg, 0.5);
  s.hold(2.0);
  ASSERT_EQ(s.steps.back(), Step::Done);
  const nlohmann::json r = s.task.result();
  EXPECT_TRUE(r["timed_out"].get<bool>());
  EXPECT_TRUE(r["acquisitions"][0]["movement_time_s"].is_null());
  EXPECT_TRUE(r["acquisitions"][2]["endpoint_deg"].is_null());
}

}  // namespace
}  // namespace knoblab::test

namespace knoblab::test {
namespace {

TEST(PointingTask, EndsATrialWhoseHomeDiskIsNeverReachedAsTimedOut) {
  const study::Protocol p = shortened_pointing();
  studyrun::PointingTiming timing;
  timing.home_timeout_s = 1;
  Script s(studyrun::PointingTask(p, trial_towards(1, 30, 11.3), timing));
  s.theta = 20 * kDeg;
  s.hold(1.1);
  ASSERT_EQ(s.steps.back(), Step::Done);
  EXPECT_EQ(std::count(s.steps.begin(), s.steps.end(), Step::Onset), 0);
  EXPECT_TRUE(s.task.result()["timed_out"].get<bool>());
}

}  // namespace
}  // namespace knoblab::test
