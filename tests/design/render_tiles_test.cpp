// The design as hapticd renders it, and a render model read back.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fan_knob_steps.hpp"
#include "knoblab/design/curve.hpp"
#include "knoblab/design/render_tiles.hpp"
#include "knoblab/jsonread/json_reader.hpp"

namespace knoblab::design {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

TEST(RenderTiles, TheFanKnobBecomesPositionTilesForItsWallsDetentsDampingAndMass) {
  const json args = load_tiles_args(testing::fan_knob());
  ASSERT_TRUE(args.contains("position"));
  EXPECT_FALSE(args.contains("time"));
  const json& p = args["position"];
  ASSERT_EQ(p.size(), 3u + 3u + 1u);
  EXPECT_TRUE(p[1].contains("torque"));  // the four clicks
  EXPECT_DOUBLE_EQ(p[1]["theta_min"].get<double>(), testing::kDetentsFrom);
  EXPECT_DOUBLE_EQ(p[1]["torque"]["x"].front().get<double>(), testing::kDetentsFrom);
  EXPECT_DOUBLE_EQ(p[1]["torque"]["x"].back().get<double>(), testing::kDetentsTo);
  EXPECT_TRUE(p[3].contains("torque_of_velocity"));
  EXPECT_EQ(p[3]["torque_of_velocity"]["x"].front(), -20.0);  // over θ̇: not stretched
  EXPECT_TRUE(p[6].contains("mass"));
}

TEST(RenderTiles, OnlyChannelsThatPlayAndTheirActiveLinesAreRendered) {
  Design d = testing::fan_knob();
  d.lines(Channel::Velocity).play = false;
  d.lines(Channel::Acceleration).lines[0].active = false;
  const json args = load_tiles_args(d);
  EXPECT_EQ(args["position"].size(), 3u);
  d.lines(Channel::Position).play = false;
  EXPECT_EQ(load_tiles_args(d), json::object());  // clears what plays
}

TEST(RenderTiles, TimeTilesRunOnTheirOwnClockFromWhereTheyStart) {
  Design d = testing::fan_knob();
  place_tile(d, Channel::Time, 0, d.palette[0].tiles[1], 0.5, 0.75);
  d.time_loop = true;
  const json t = load_tiles_args(d)["time"][0];
  EXPECT_EQ(t["start"], 0.5);
  EXPECT_EQ(t["duration"], 0.25);
  EXPECT_EQ(t["torque"]["x"].front(), 0.0);
  EXPECT_DOUBLE_EQ(t["torque"]["x"].back().get<double>(), 0.25);
  EXPECT_EQ(t["period"], 0.75);
}

TEST(RenderTiles, ARenderModelReadBackRendersTheSameAgain) {
  Design d = testing::fan_knob();
  place_tile(d, Channel::Time, 0, d.palette[0].tiles[1], 0.5, 0.75);
  const json args = load_tiles_args(d);
  const Design back = design_from_load_tiles(args, "imported");
  EXPECT_EQ(back.lines(Channel::Position).lines[0].tiles.size(), 3u);
  EXPECT_EQ(load_tiles_args(back), args);
}

TEST(RenderTiles, ARenderModelWithoutThePrototypersCurvesIsRefusedNamingTheTile) {
  const json args = json::parse(R"({"position":[{"theta_min":0,"theta_max":1,"f_vel":{"x":[0,1],"y":[0.001,0.001]}}]})");
  try {
    design_from_load_tiles(args, "x");
    FAIL();
  } catch (const jsonread::PathError& e) {
    EXPECT_THAT(e.what(), HasSubstr("position[0]"));
  }
}

}  // namespace
}  // namespace knoblab::design
