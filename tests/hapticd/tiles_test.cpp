// Prototyper tiles from the protocol to the knob: load_tiles' arguments are
// checked (curves that are functions, no energy fed in, nothing the torque
// limit would clip), a set loads in any mode and is felt in render mode,
// and loading twice in a row works.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "core_harness.hpp"
#include "knoblab/hal/memory_lines.hpp"
#include "knoblab/hapticd/control_handler.hpp"
#include "knoblab/hapticd/daemon.hpp"
#include "knoblab/hapticd/render_controller.hpp"
#include "knoblab/hapticd/tiles_json.hpp"
#include "shared_host.hpp"

namespace knoblab::hapticd {
namespace {

using nlohmann::json;

const SafetyLimits kLimits{};

std::optional<ParamProblem> problem_of(const json& args) {
  auto r = tiles_from_json(args, kLimits);
  if (auto* p = std::get_if<ParamProblem>(&r)) return *p;
  return std::nullopt;
}

json damping_tile(json y) {
  return {{"theta_min", -1.0}, {"theta_max", 1.0}, {"f_vel", {{"x", {-1.0, -0.5, 0.0, 0.5, 1.0}}, {"y", y}}}};
}

TEST(TilesJson, ADesignedSetParsesIntoPositionAndTimeTilesInOrder) {
  const json args = {
      {"position", {damping_tile({0.001, 0.001, 0.002, 0.001, 0.001}),
                    {{"theta_min", 0.0}, {"theta_max", 6.283},
                     {"f_acc", {{"x", {0.0, 3.1416, 6.2832}}, {"y", {1e-5, 2e-5, 1e-5}}, {"periodic", true}}}}}},
      {"time", {{{"duration", 0.2}, {"loop", true}, {"f_pos", {{"x", {0.0, 0.2}}, {"y", {0.0, 0.01}}}}}}}};
  auto r = tiles_from_json(args, kLimits);
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<TileSet>>(r)) << std::get<ParamProblem>(r).message;
  const TileSet& set = *std::get<std::unique_ptr<TileSet>>(r);
  ASSERT_EQ(set.position.size(), 2u);
  ASSERT_EQ(set.time.size(), 1u);
  EXPECT_TRUE(set.position[0].f_vel && !set.position[0].f_pos);
  EXPECT_EQ(set.position[1].f_acc->boundary(), model::SplineBoundary::kPeriodic);
  EXPECT_TRUE(set.time[0].loop);
  EXPECT_NEAR((*set.position[0].f_vel)(0.0), 0.002, 1e-12);
}

TEST(TilesJson, ATimeTileStartsWhereItIsPlacedAndALoopCannotRepeatBeforeTheTileHasEnded) {
  const json torque = {{"x", {0.0, 0.25}}, {"y", {0.0, 0.01}}};
  auto r = tiles_from_json({{"time", {{{"start", 0.5}, {"duration", 0.25}, {"loop", true}, {"period", 1.0}, {"torque", torque}}}}},
                           kLimits);
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<TileSet>>(r)) << std::get<ParamProblem>(r).message;
  const model::TimeTile& t = std::get<std::unique_ptr<TileSet>>(r)->time.at(0);
  EXPECT_EQ(t.start, 0.5);
  EXPECT_EQ(t.period, 1.0);
  const auto p = problem_of({{"time", {{{"start", 0.5}, {"duration", 0.25}, {"loop", true}, {"period", 0.6}, {"torque", torque}}}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "time[0].period");
  EXPECT_EQ(p->message, "time[0].period: must be at least start + duration (0.75 s): a tile cannot repeat before it has ended");
}

TEST(TilesJson, KnotsThatDoNotIncreaseAreRefusedNamingTheCurve) {
  json tile = damping_tile({0.001, 0.001, 0.001, 0.001, 0.001});
  tile["f_vel"]["x"] = {-1.0, 0.0, 0.0, 0.5, 1.0};
  const auto p = problem_of({{"time", json::array()}, {"position", {damping_tile({0.001, 0.001, 0.001, 0.001, 0.001}), tile}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[1].f_vel");
  EXPECT_NE(p->message.find("increase strictly"), std::string::npos) << p->message;
}

TEST(TilesJson, CurvesWithMoreKnotsThanValuesAreRefused) {
  json tile = damping_tile({0.001, 0.001, 0.001, 0.001});
  const auto p = problem_of({{"position", {tile}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].f_vel");
  EXPECT_NE(p->message.find("5 knots but y has 4"), std::string::npos) << p->message;
}

TEST(TilesJson, DampingThatDipsBelowZeroBetweenItsKnotsIsRefused) {
  // Every knot is ≥ 0, but the natural cubic through a lone bump undershoots.
  const auto p = problem_of({{"position", {damping_tile({0.0, 0.0, 0.01, 0.0, 0.0})}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].f_vel");
  EXPECT_NE(p->message.find("feed energy"), std::string::npos) << p->message;
  // Negative mass on a time tile, too.
  const auto q = problem_of({{"time", {{{"duration", 1.0}, {"f_acc", {{"x", {0.0, 1.0}}, {"y", {0.0, -1e-5}}}}}}}});
  ASSERT_TRUE(q);
  EXPECT_EQ(q->key, "time[0].f_acc");
}

TEST(TilesJson, ASpringTileBeyondTheTorqueLimitIsRefusedBeforeItPlays) {
  // 0.1 N·m/rad × 3 rad = 300 mN·m at the end of the range: over 180.
  const json spring = {{"theta_min", -3.0}, {"theta_max", 3.0}, {"f_pos", {{"x", {-3.0, 3.0}}, {"y", {0.1, 0.1}}}}};
  const auto p = problem_of({{"position", {spring}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].f_pos");
  EXPECT_NE(p->message.find("torque limit of 180 mN·m"), std::string::npos) << p->message;
  json gentle = spring;
  gentle["f_pos"]["y"] = {0.05, 0.05};  // 150 mN·m at most
  EXPECT_FALSE(problem_of({{"position", {gentle}}}));
}

TEST(TilesJson, ATileWhoseRangeIsEmptyIsRefused) {
  json tile = damping_tile({0.001, 0.001, 0.001, 0.001, 0.001});
  tile["theta_max"] = -1.0;
  const auto p = problem_of({{"position", {tile}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].theta_max");
}

// ---- torque-valued curves and the loop's stability ----

json curve(std::vector<double> x, std::vector<double> y) { return {{"x", x}, {"y", y}}; }

json torque_tile(double lo, double hi, double slope) {
  return {{"theta_min", lo}, {"theta_max", hi}, {"torque", curve({lo, hi}, {slope * lo, slope * hi})}};
}

TEST(TilesJson, TorqueVelocityTorqueAndMassCurvesParseIntoTheTiles) {
  const json args = {
      {"position",
       {{{"theta_min", -1.0},
         {"theta_max", 1.0},
         {"torque", curve({-1.0, 0.0, 1.0}, {0.0, 0.02, 0.0})},
         {"torque_of_velocity", curve({-2.0, 2.0}, {-0.004, 0.004})},
         {"mass", curve({-1.0, 1.0}, {1e-5, 1e-5})}}}},
      {"time", {{{"duration", 0.5}, {"torque", curve({0.0, 0.5}, {0.0, 0.05})}}}}};
  auto r = tiles_from_json(args, kLimits);
  ASSERT_TRUE(std::holds_alternative<std::unique_ptr<TileSet>>(r)) << std::get<ParamProblem>(r).message;
  const TileSet& set = *std::get<std::unique_ptr<TileSet>>(r);
  EXPECT_NEAR(set.position[0].torque({0.0, 1.0, 0.0}), 0.02 + 0.002, 1e-12);
  EXPECT_NEAR(set.position[0].mass_at(0.3), 1e-5, 1e-15);
  EXPECT_NEAR(set.time[0].torque(0.25, {}), 0.025, 1e-12);
}

TEST(TilesJson, TorqueCurvesBeyondTheTorqueLimitAreRefusedNamingTheCurve) {
  auto p = problem_of({{"position", {{{"theta_min", 0.0}, {"theta_max", 1.0}, {"torque", curve({0.0, 1.0}, {0.0, 0.2})}}}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].torque");
  EXPECT_NE(p->message.find("beyond the device's torque limit of 180 mN·m"), std::string::npos) << p->message;
  // 4 mN·m·s/rad is 200 mN·m at the 50 rad/s velocity limit, though only
  // 8 mN·m at its last knot: the line goes on.
  p = problem_of({{"position", {{{"theta_min", 0.0}, {"theta_max", 1.0}, {"torque_of_velocity", curve({-2.0, 2.0}, {-0.008, 0.008})}}}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].torque_of_velocity");
  EXPECT_NE(p->message.find("reaches -200 mN·m at θ̇ = -50 rad/s"), std::string::npos) << p->message;
  p = problem_of({{"time", {{{"duration", 1.0}, {"torque", curve({0.0, 1.0}, {0.0, -0.25})}}}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "time[0].torque");
}

TEST(TilesJson, MassBelowZeroBetweenKnotsOrAboveTheRenderersMaximumIsRefused) {
  auto p = problem_of({{"position", {{{"theta_min", -1.0}, {"theta_max", 1.0},
                                      {"mass", curve({-1.0, -0.5, 0.0, 0.5, 1.0}, {0.0, 0.0, 1e-4, 0.0, 0.0})}}}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].mass");
  EXPECT_NE(p->message.find("below zero"), std::string::npos) << p->message;
  p = problem_of({{"position", {{{"theta_min", -1.0}, {"theta_max", 1.0}, {"mass", curve({-1.0, 1.0}, {1e-3, 2e-3})}}}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].mass");
  EXPECT_NE(p->message.find("1.5 mN·m/(rad/s²)"), std::string::npos) << p->message;
  // Two tiles within it alone, beyond it where they overlap.
  const json half = {{"theta_min", -1.0}, {"theta_max", 1.0}, {"mass", curve({-1.0, 1.0}, {1e-3, 1e-3})}};
  EXPECT_FALSE(problem_of({{"position", {half}}}));
  p = problem_of({{"position", {half, half}}});
  ASSERT_TRUE(p);
  EXPECT_NE(p->message.find("together"), std::string::npos) << p->message;
}

std::string four_digits(double v) {  // as refusals print numbers
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

const model::LoopStability& default_loop() {
  static const model::LoopStability loop{RenderController::loop_dynamics(10000.0)};
  return loop;
}

TEST(TilesJson, AStiffnessBeyondTheLoopsStableRegionIsRefusedInNumbers) {
  const double k_max = default_loop().max_stiffness(0.0);
  // A spring as stiff as 1.5 × the bound over a span where its torque stays
  // within the limit.
  const double k = 1.5 * k_max, span = 0.15 / k;
  const auto p = problem_of({{"position", {torque_tile(-span, span, k)}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].torque");
  EXPECT_NE(p->message.find("its stiffness reaches " + four_digits(k) + " N·m/rad"), std::string::npos)
      << p->message;
  EXPECT_NE(p->message.find("beyond the 10 kHz loop's stable " + four_digits(k_max) + " N·m/rad with 0 N·m·s/rad damping there"),
            std::string::npos)
      << p->message;
  EXPECT_FALSE(problem_of({{"position", {torque_tile(-span, span, 0.8 * k_max)}}}));
}

TEST(TilesJson, OverlappingStiffTilesAddUpAgainstTheStableRegion) {
  const double k = 0.6 * default_loop().max_stiffness(0.0), span = 0.08 / k;
  const json one = torque_tile(-span, span, k);
  EXPECT_FALSE(problem_of({{"position", {one}}}));
  const auto p = problem_of({{"position", {one, one}}});
  ASSERT_TRUE(p);
  EXPECT_NE(p->message.find("the tiles there together"), std::string::npos) << p->message;
  // The same spring as f_pos (Eq. 19): its stiffness is d(f_pos·θ)/dθ.
  const json spring = {{"theta_min", -span}, {"theta_max", span}, {"f_pos", curve({-span, span}, {k, k})}};
  const auto q = problem_of({{"position", {one, spring}}});
  ASSERT_TRUE(q);
}

// A damping curve changes B at every point it is checked at, so each point
// is tested on its own: the check refuses the curve where it has risen past
// the loop's stable damping, and passes the same curve scaled inside it.
TEST(TilesJson, ADampingCurveIsRefusedWhereItRisesBeyondTheStableDamping) {
  const double b_max = default_loop().max_damping(0.0);
  const json over = damping_tile({0.1 * b_max, 0.5 * b_max, 0.9 * b_max, 1.3 * b_max, 1.6 * b_max});
  const auto p = problem_of({{"position", {over}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].f_vel");
  EXPECT_NE(p->message.find("its damping reaches"), std::string::npos) << p->message;
  // Where it crossed: past θ = 0 (0.9 × the bound), before θ = 0.5 (1.3 ×).
  const auto at = p->message.find("at θ = ");
  ASSERT_NE(at, std::string::npos) << p->message;
  const double theta = std::stod(p->message.substr(at + std::string("at θ = ").size()));
  EXPECT_GT(theta, 0.0) << p->message;
  EXPECT_LT(theta, 0.5) << p->message;
  const json inside = damping_tile({0.05 * b_max, 0.25 * b_max, 0.45 * b_max, 0.65 * b_max, 0.8 * b_max});
  EXPECT_FALSE(problem_of({{"position", {inside}}}));
}

TEST(TilesJson, ADampingDownSlopeSteeperThanTheGripIsRefused) {
  // A local fall of more than 20 mN·m·s/rad around rest, twice the grip's
  // damping, flat beyond 0.5 rad/s (so within the torque limit at any speed).
  const std::vector<double> v = {-50.0, -0.5, -0.05, 0.0, 0.05, 0.5, 50.0};
  const json tile = {{"theta_min", -3.0}, {"theta_max", 3.0},
                     {"torque_of_velocity", curve(v, {0.0, 0.0, 0.001, 0.0, -0.001, 0.0, 0.0})}};
  const auto p = problem_of({{"position", {tile}}});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->key, "position[0].torque_of_velocity");
  EXPECT_NE(p->message.find("falls to"), std::string::npos) << p->message;
  json gentle = tile;
  gentle["torque_of_velocity"] = curve(v, {0.0, 0.0, 0.0002, 0.0, -0.0002, 0.0, 0.0});
  EXPECT_FALSE(problem_of({{"position", {gentle}}})) << "a down-slope the grip outweighs renders";
}

// ---- in the loop ----

TEST(Tiles, ASpringTileLoadedWhileIdleIsFeltOnEnteringRender) {
  sim::PlantConfig plant = testing::plant_with("high-inertia");
  plant.initial_angle = 0.5;
  testing::CoreHarness h(plant);
  h.set_render(0.0, 0.0);  // a model that renders nothing by itself
  h.run(10);
  auto set = std::make_unique<TileSet>();
  model::PositionTile spring;
  const std::vector<double> x = {-2.0, 2.0}, k = {0.05, 0.05};
  spring.f_pos = model::CubicSpline(x, k);
  spring.theta_min = -2.0;
  spring.theta_max = 2.0;
  set->position.push_back(spring);
  ASSERT_TRUE(h.core().load_tiles(std::move(set)));
  h.run(1);  // idle: taken, not rendered
  EXPECT_FALSE(h.last_out.amp_enable);
  h.command(CoreCommand::SetMode, Mode::Render);
  const LoopRecord first = h.step();
  const double tpv = h.core().config().limits.torque_per_volt;
  // τ = f_pos(θ)·θ against the knob: the motor pushes with −τ.
  EXPECT_NEAR(-first.sample.command * tpv, 0.05 * first.sample.theta, 2e-4) << "θ = " << first.sample.theta;
  EXPECT_GT(first.sample.theta, 0.45);
  ASSERT_TRUE(h.core().load_tiles(nullptr));
  h.run(600);  // faded out over the ramp
  EXPECT_NEAR(h.records.back().sample.command, 0.0, 1e-3);
}

TEST(LoadTiles, TwoSetsInARowBothReachTheLoopAndGetStateCountsTheLoadedOne) {
  DaemonConfig cfg;
  cfg.core.rate_hz = 10000.0;
  shared_host::configure(cfg);
  Daemon d(cfg, std::make_unique<capture::SimDaq>(testing::plant_with("moderate-detents"), 10000.0),
           std::make_unique<hal::MemoryLines>(false));
  ControlHandler handler(d, {});
  rt::LoopResult timing;
  std::thread loop([&] { timing = d.run(); });

  control::Request load;
  load.command = control::Command::load_tiles;
  load.args = {{"position", {damping_tile({0.001, 0.001, 0.002, 0.001, 0.001})}}};
  control::Reply first = handler.handle(load);
  ASSERT_TRUE(first.ok) << first.error.message;
  load.args["time"] = {{{"duration", 0.5}, {"f_vel", {{"x", {0.0, 0.5}}, {"y", {0.0, 0.001}}}}}};
  control::Reply second = handler.handle(load);  // at once: the loop must take the first meanwhile
  ASSERT_TRUE(second.ok) << second.error.message;
  EXPECT_EQ(second.result["position"], 1);
  EXPECT_EQ(second.result["time"], 1);

  control::Request state;
  state.command = control::Command::get_state;
  EXPECT_EQ(handler.handle(state).result["tiles"], (json{{"position", 1}, {"time", 1}}));
  control::Request clear;
  clear.command = control::Command::load_tiles;
  clear.args = json::object();
  ASSERT_TRUE(handler.handle(clear).ok);
  EXPECT_EQ(handler.handle(state).result["tiles"], (json{{"position", 0}, {"time", 0}}));

  load.args = {{"position", {damping_tile({0.0, 0.0, -0.001, 0.0, 0.0})}}};
  control::Reply bad = handler.handle(load);
  EXPECT_FALSE(bad.ok);
  EXPECT_EQ(bad.error.code, control::ErrorCode::bad_args);
  EXPECT_EQ(bad.error.key, "position[0].f_vel");
  d.stop();
  loop.join();
  shared_host::report_timing(timing);
}

}  // namespace
}  // namespace knoblab::hapticd
