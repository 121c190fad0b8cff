// Undo and redo round-trip every kind of edit: after undo the design is the
// one before the edit, after redo the one after it, in a design that holds
// something of everything (the fan knob).
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fan_knob_steps.hpp"
#include "knoblab/design/edits.hpp"
#include "knoblab/design/history.hpp"

namespace knoblab::design {
namespace {

using testing::fan_knob;

struct EditCase {
  std::string name;
  std::function<void(Design&)> edit;
};

std::vector<EditCase> every_edit() {
  const TileRef detents{Channel::Position, 0, 1}, wall{Channel::Position, 0, 0}, damping{Channel::Velocity, 0, 1};
  return {
      {"set_editor", [](Design& d) { set_editor(d, {{{0, 0}, {1, 0.01}}, false}, Channel::Time); }},
      {"move_point", [](Design& d) { move_point(d, 1, {0.0, 0.007}); }},
      {"add_point", [](Design& d) { add_point(d, {3.3, 0.001}); }},
      {"remove_point", [](Design& d) { remove_point(d, 1); }},
      {"scale_selection horizontal", [](Design& d) { scale_selection(d, {-5, 5}, Mirror::Horizontal, 0.001, 1.5); }},
      {"scale_selection vertical", [](Design& d) { scale_selection(d, {-100, 100}, Mirror::Vertical, 0.0, 0.5); }},
      {"add_tab", [](Design& d) { add_tab(d, "scratch"); }},
      {"rename_tab", [](Design& d) { rename_tab(d, 1, "Fan"); }},
      {"remove_tab", [](Design& d) { remove_tab(d, 1); }},
      {"add_tile", [](Design& d) { add_tile(d, 1, tile_from_selection(d, {-5, 5}, "part")); }},
      {"rename_tile", [](Design& d) { rename_tile(d, 1, 0, "4 clicks"); }},
      {"remove_tile", [](Design& d) { remove_tile(d, 1, 0); }},
      {"edit_tile", [](Design& d) { edit_tile(d, 0, 0); }},
      {"place_tile on a new line", [](Design& d) { place_tile(d, Channel::Position, 1, d.palette[0].tiles[1], 0.1, 0.4); }},
      {"move_tile", [detents](Design& d) { move_tile(d, detents, 0.0); }},
      {"resize_tile", [detents](Design& d) { resize_tile(d, detents, -0.2, 1.5); }},
      {"remove_placed", [wall](Design& d) { remove_placed(d, wall); }},
      {"superimpose", [detents, wall](Design& d) { superimpose(d, detents, wall); }},
      {"superimpose velocity", [](Design& d) {
         place_tile(d, Channel::Velocity, 1, d.palette[0].tiles[5], testing::kDetentsFrom, testing::kDetentsTo);
         superimpose(d, {Channel::Velocity, 0, 1}, {Channel::Velocity, 1, 0});
       }},
      {"add_line", [](Design& d) { add_line(d, Channel::Time); }},
      {"remove_line", [](Design& d) { remove_line(d, Channel::Velocity, 0); }},
      {"set_line_active", [](Design& d) { set_line_active(d, Channel::Position, 0, false); }},
      {"set_channel_play", [](Design& d) { set_channel_play(d, Channel::Acceleration, false); }},
      {"set_time_loop", [](Design& d) { set_time_loop(d, true); }},
      {"rename_design", [](Design& d) { rename_design(d, "fan knob 2"); }},
      {"place_tile in time", [damping](Design& d) {
         (void)damping;
         place_tile(d, Channel::Time, 0, d.palette[0].tiles[1], 0.0, 0.2);
       }},
  };
}

TEST(History, EveryKindOfEditIsUndoneToTheDesignBeforeItAndRedoneToTheDesignAfterIt) {
  const Design start = fan_knob();
  for (const EditCase& c : every_edit()) {
    SCOPED_TRACE(c.name);
    History h(start);
    h.apply(c.name, c.edit);
    const Design after = h.design();
    ASSERT_NE(after, start) << "the edit changed nothing";
    EXPECT_EQ(h.undo(), c.name);
    EXPECT_EQ(h.design(), start);
    EXPECT_EQ(h.redo(), c.name);
    EXPECT_EQ(h.design(), after);
  }
}

TEST(History, TheWholeFanKnobUndoesStepByStepToNothingAndRedoesToTheSameDesign) {
  History h;
  testing::build_fan_knob(h);
  const Design built = h.design();
  int steps = 0;
  while (h.can_undo()) {
    h.undo();
    ++steps;
  }
  EXPECT_EQ(steps, 14);
  EXPECT_EQ(h.design(), Design{});
  while (h.can_redo()) h.redo();
  EXPECT_EQ(h.design(), built);
}

TEST(History, ARefusedEditChangesNothingAndLeavesUndoAsItWas) {
  History h(fan_knob());
  h.apply("renamed", [](Design& d) { rename_design(d, "x"); });
  const Design before = h.design();
  EXPECT_THROW(h.apply("bad", [](Design& d) { remove_point(d, 999); }), EditError);
  EXPECT_EQ(h.design(), before);
  EXPECT_EQ(h.undo_label(), "renamed");
}

TEST(History, ANewEditAfterUndoClearsRedo) {
  History h(fan_knob());
  h.apply("a", [](Design& d) { rename_design(d, "a"); });
  h.undo();
  ASSERT_TRUE(h.can_redo());
  h.apply("b", [](Design& d) { rename_design(d, "b"); });
  EXPECT_FALSE(h.can_redo());
  EXPECT_EQ(h.design().name, "b");
}

TEST(History, AnEditThatChangesNothingIsNotAStepToUndo) {
  History h(fan_knob());
  h.apply("same", [](Design& d) { set_channel_play(d, Channel::Position, true); });
  EXPECT_FALSE(h.can_undo());
}

TEST(History, ModifiedSaysWhetherTheDesignDiffersFromTheOneSaved) {
  History h;
  h.reset(fan_knob());
  EXPECT_FALSE(h.modified());
  h.apply("r", [](Design& d) { rename_design(d, "r"); });
  EXPECT_TRUE(h.modified());
  h.mark_saved();
  EXPECT_FALSE(h.modified());
  h.undo();
  EXPECT_TRUE(h.modified());
}

}  // namespace
}  // namespace knoblab::design
