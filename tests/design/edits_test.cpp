// What each edit does to the curve and the pane, and the sentences it
// refuses with.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fan_knob_steps.hpp"
#include "knoblab/design/curve.hpp"
#include "knoblab/design/edits.hpp"
#include "knoblab/design/templates.hpp"

namespace knoblab::design {
namespace {

using ::testing::HasSubstr;

Design with_editor(Waveform w) {
  Design d = new_design("t");
  set_editor(d, w, Channel::Position);
  return d;
}

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const EditError& e) {
    return e.what();
  }
  return "(not refused)";
}

TEST(Edits, ADraggedPointStopsShortOfItsNeighboursInsteadOfPassingThem) {
  Design d = with_editor({{{0, 0}, {1, 1}, {2, 0}}, false});
  move_point(d, 1, {5.0, 0.5});
  EXPECT_LT(d.editor.waveform.points[1].x, 2.0);
  EXPECT_GT(d.editor.waveform.points[1].x, 1.99);
  EXPECT_EQ(d.editor.waveform.points[1].y, 0.5);
  EXPECT_TRUE(waveform_problem(d.editor.waveform).empty());
}

TEST(Edits, AnAddedPointGoesInXOrderAndOneOnTopOfAnotherIsRefused) {
  Design d = with_editor({{{0, 0}, {2, 0}}, false});
  add_point(d, {1, 0.3});
  ASSERT_EQ(d.editor.waveform.points.size(), 3u);
  EXPECT_EQ(d.editor.waveform.points[1], (Point{1, 0.3}));
  EXPECT_EQ(refusal([&] { add_point(d, {1, 0.1}); }), "There is already a point there.");
}

TEST(Edits, AWaveformKeepsTwoPoints) {
  Design d = with_editor({{{0, 0}, {2, 0}}, false});
  EXPECT_EQ(refusal([&] { remove_point(d, 0); }), "A waveform keeps at least 2 points.");
}

TEST(Edits, AHorizontalMirrorLineStretchesTheSelectedPointsAwayFromIt) {
  Design d = with_editor({{{0, 0.01}, {1, 0.03}, {2, -0.01}, {3, 0.0}}, false});
  scale_selection(d, {0.5, 2.5}, Mirror::Horizontal, 0.01, 2.0);
  const auto& p = d.editor.waveform.points;
  EXPECT_DOUBLE_EQ(p[0].y, 0.01);   // outside the selection
  EXPECT_DOUBLE_EQ(p[1].y, 0.05);   // 0.01 + 2·(0.03 − 0.01)
  EXPECT_DOUBLE_EQ(p[2].y, -0.03);  // 0.01 + 2·(−0.01 − 0.01)
  EXPECT_DOUBLE_EQ(p[3].y, 0.0);
}

TEST(Edits, AVerticalMirrorLineStretchesXAndANegativeFactorMirrorsTheCurve) {
  Design d = with_editor({{{0, 0}, {1, 0.02}, {2, 0.01}}, false});
  scale_selection(d, {-1, 3}, Mirror::Vertical, 1.0, -1.0);
  const auto& p = d.editor.waveform.points;
  EXPECT_EQ(p[0], (Point{0, 0.01}));
  EXPECT_EQ(p[1], (Point{1, 0.02}));
  EXPECT_EQ(p[2], (Point{2, 0}));
  EXPECT_THAT(refusal([&] { scale_selection(d, {0.5, 1.5}, Mirror::Vertical, 0.0, 3.0); }),
              HasSubstr("would overlap the points beside it"));
  EXPECT_EQ(refusal([&] { scale_selection(d, {5, 6}, Mirror::Horizontal, 0, 2); }),
            "No points are selected: drag across the waveform first.");
}

TEST(Edits, ATileFromASelectionStartsAndEndsOnTheCurveAndKeepsThePointsInside) {
  Design d = with_editor(detent_series().waveform);
  const model::CubicSpline curve = spline_of(d.editor.waveform);
  const Tile t = tile_from_selection(d, {0.1, 1.0}, "part");
  EXPECT_EQ(t.waveform.points.front().x, 0.1);
  EXPECT_DOUBLE_EQ(t.waveform.points.front().y, curve(0.1));
  EXPECT_EQ(t.waveform.points.back().x, 1.0);
  EXPECT_DOUBLE_EQ(t.waveform.points.back().y, curve(1.0));
  for (const Point& p : t.waveform.points) {
    EXPECT_GE(p.x, 0.1);
    EXPECT_LE(p.x, 1.0);
  }
  EXPECT_EQ(t.waveform.points.size(), 2u + 14u);  // knots every 2π/96 rad strictly inside (0.1, 1.0)
}

TEST(Edits, ResizingAPositionTileChangesItsFrequency) {
  Design d = testing::fan_knob();
  const TileRef detents{Channel::Position, 0, 1};
  resize_tile(d, detents, testing::kDetentsFrom, testing::kDetentsFrom + 60 * testing::kDeg);
  const PlacedTile& p = d.lines(Channel::Position).lines[0].tiles[1];
  const Waveform w = placed_waveform(p, Channel::Position);
  const model::CubicSpline s = spline_of(w);
  // Four detents now in 60°: the torque rises through 0 every 15°.
  for (int k = 0; k < 4; ++k) {
    const double rest = testing::kDetentsFrom + (7.5 + 15.0 * k) * testing::kDeg;
    EXPECT_NEAR(s(rest), 0.0, 2e-4) << k;
    EXPECT_GT(s.derivative(rest), 0.0) << k;
  }
}

TEST(Edits, MovingATileKeepsItsLengthAndTheLineInOrder) {
  Design d = testing::fan_knob();
  move_tile(d, {Channel::Position, 0, 0}, 3.0);  // the anticlockwise wall, past the others
  const auto& tiles = d.lines(Channel::Position).lines[0].tiles;
  EXPECT_EQ(tiles.back().from, 3.0);
  EXPECT_DOUBLE_EQ(tiles.back().to - tiles.back().from, testing::kWall);
  EXPECT_LT(tiles[0].from, tiles[1].from);
}

TEST(Edits, SuperimposingTwoTilesGivesOneTileThatIsTheirSum) {
  Design d = testing::fan_knob();
  const PlacedTile detents = d.lines(Channel::Position).lines[0].tiles[1];
  place_tile(d, Channel::Position, 1, ramp(), 0.0, 1.0);
  const PlacedTile r = d.lines(Channel::Position).lines[1].tiles[0];
  superimpose(d, {Channel::Position, 0, 1}, {Channel::Position, 1, 0});
  EXPECT_TRUE(d.lines(Channel::Position).lines[1].tiles.empty());
  const PlacedTile& sum = d.lines(Channel::Position).lines[0].tiles[1];
  EXPECT_EQ(sum.tile.name, "four clicks + ramp");
  EXPECT_DOUBLE_EQ(sum.from, detents.from);
  EXPECT_DOUBLE_EQ(sum.to, detents.to);
  const model::CubicSpline s = spline_of(placed_waveform(sum, Channel::Position)),
                           a = spline_of(placed_waveform(detents, Channel::Position)),
                           b = spline_of(placed_waveform(r, Channel::Position));
  for (double th = 0.05; th < 0.9; th += 0.1) EXPECT_NEAR(s(th), a(th) + b(th), 2e-4) << th;   // both
  for (double th = 1.2; th < detents.to - 0.1; th += 0.1) EXPECT_NEAR(s(th), a(th), 2e-4) << th;  // detents only
}

TEST(Edits, TilesOfDifferentChannelsDoNotSuperimpose) {
  Design d = testing::fan_knob();
  EXPECT_EQ(refusal([&] { superimpose(d, {Channel::Position, 0, 1}, {Channel::Velocity, 0, 1}); }),
            "Only tiles of one channel add up: both must be in the same channel.");
}

TEST(Edits, ATileThatEndsBeforeItStartsOrATimeTileBeforeZeroIsRefused) {
  Design d = testing::fan_knob();
  EXPECT_THAT(refusal([&] { resize_tile(d, {Channel::Position, 0, 1}, 1.0, 0.5); }),
              HasSubstr("A tile must end after it starts (1 rad to 0.5 rad)."));
  EXPECT_EQ(refusal([&] { place_tile(d, Channel::Time, 0, ramp(), -0.1, 0.2); }), "Time tiles start at 0 s or later.");
  EXPECT_EQ(refusal([&] { place_tile(d, Channel::Time, 3, ramp(), 0.0, 0.2); }),
            "The time channel has 0 lines; place on one of them or start a new one.");
}

TEST(Edits, EditsOnAnEmptyEditorSayWhatToDoFirst) {
  Design d = new_design("t");
  EXPECT_EQ(refusal([&] { add_point(d, {0, 0}); }), "The editor is empty: drag a tile or a template into it first.");
}

}  // namespace
}  // namespace knoblab::design
