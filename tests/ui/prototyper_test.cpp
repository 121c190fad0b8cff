// The Haptic Icon Prototyper driven by touch on the real screen (offscreen)
// against hapticd on the sim backend: the thesis' fan knob (§5.3, Fig. 70)
// built from the templates as tests/design/fan_knob_steps.hpp builds it, by
// drags and taps on the screen's items, saved, reopened and equal to the
// steps' design; undo and redo from the screen's buttons; a malformed file
// named in the message bar; and the design played on hapticd.
#include <gtest/gtest.h>

#include <QTest>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

#include "fan_knob_steps.hpp"
#include "kiosk.hpp"
#include "knoblab/design/design_json.hpp"
#include "knoblab/design/render_tiles.hpp"
#include "process.hpp"

namespace knoblab::ui {
namespace {

namespace steps = design::testing;

QPointF centre(const QQuickItem* i) { return i->mapToScene(QPointF(i->width() / 2, i->height() / 2)); }

// A finger pressed at `from`, moved in steps as a finger moves to where
// `to()` says (asked again once the drag has begun: the screen may make room
// for the drop then), and lifted there.
void drag(QQuickWindow* window, QPointF from, const std::function<QPointF()>& to) {
  QTest::mousePress(window, Qt::LeftButton, Qt::NoModifier, from.toPoint());
  Screen::wait(50);
  for (int k = 1; k <= 4; ++k) {  // past the drag threshold
    QTest::mouseMove(window, (from + QPointF(0, -8.0 * k)).toPoint());
    Screen::wait(40);
  }
  const QPointF start = from + QPointF(0, -32);
  const QPointF end = to();
  for (int k = 1; k <= 12; ++k) {
    QTest::mouseMove(window, (start + (end - start) * (k / 12.0)).toPoint());
    Screen::wait(30);
  }
  Screen::wait(100);
  QTest::mouseRelease(window, Qt::LeftButton, Qt::NoModifier, end.toPoint());
  Screen::wait(300);
}

// A tile's edge, or a tile, dragged along x only to `x` (scene).
void drag_x(QQuickWindow* window, QPointF from, double x) {
  QTest::mousePress(window, Qt::LeftButton, Qt::NoModifier, from.toPoint());
  Screen::wait(50);
  const QPointF end(x, from.y());
  for (int k = 1; k <= 12; ++k) {
    QTest::mouseMove(window, (from + (end - from) * (k / 12.0)).toPoint());
    Screen::wait(30);
  }
  QTest::mouseRelease(window, Qt::LeftButton, Qt::NoModifier, end.toPoint());
  Screen::wait(300);
}

// The prototyper's window against a fresh hapticd, designs in `designs`.
struct Prototyper {
  explicit Prototyper(QSize panel = QSize(1280, 800))
      : daemon(), kiosk(daemon, "prototyper", panel, {}, QString::fromStdString(designs().string())),
        screen(kiosk.window) {}
  std::filesystem::path designs() const { return std::filesystem::path(daemon.dir()) / "designs"; }
  QQuickItem* item(const char* name) const { return screen.item(name); }
  // Where the pane draws a channel's value (rad or s): the x a finger aims at.
  double pane_x(const char* channel, double value) const {
    double x = 0.0;
    QMetaObject::invokeMethod(item("tilePane"), "sceneXOf", Q_RETURN_ARG(double, x), Q_ARG(QString, channel),
                              Q_ARG(double, value));
    return x;
  }
  // A palette tile dragged and let go on a line of the pane, the finger at
  // `value` of the channel's axis.
  void place(const char* tile, const char* line, const char* channel, double value) {
    QQuickItem* t = item(tile);
    ASSERT_NE(t, nullptr) << tile;
    drag(kiosk.window, centre(t), [&] {
      QQuickItem* l = item(line);
      EXPECT_NE(l, nullptr) << line;
      return l ? QPointF(pane_x(channel, value), centre(l).y()) : QPointF();
    });
  }
  void to_editor(const char* tile) {
    QQuickItem* t = item(tile);
    ASSERT_NE(t, nullptr) << tile;
    drag(kiosk.window, centre(t), [&] { return centre(item("editorPlot")); });
  }
  int edits() const { return kiosk.designs.revision(); }
  std::string said() const { return kiosk.messages.join(" | ").toStdString(); }

  test::Hapticd daemon;
  Kiosk kiosk;
  Screen screen;
};

TEST(Prototyper, TheFanKnobBuiltFromTheTemplatesByTouchIsSavedReopenedAndEqualToTheThesisSteps) {
  g_warnings.clear();
  Prototyper p;
  ASSERT_TRUE(p.daemon.ready()) << p.daemon.log();
  ASSERT_NE(p.kiosk.window, nullptr);
  const DesignSession& s = p.kiosk.designs;
  Screen& screen = p.screen;
  ASSERT_TRUE(spin_until([&] { return p.item("prototyperScreen") != nullptr; }, 10000));
  Screen::settle(p.item("prototyperScreen"));
  Screen::wait(300);

  // The design's name, and a tab for its tiles.
  screen.type("designName", "fan knob");
  ASSERT_TRUE(screen.tap("renameDesign"));
  ASSERT_TRUE(screen.tap("addTab"));
  screen.type("paletteName", "Fan knob");
  ASSERT_TRUE(screen.tap("renameTab"));
  ASSERT_EQ(s.design().palette.size(), 2u) << p.said();
  EXPECT_EQ(s.design().palette[1].name, "Fan knob");

  // The detent series into the editor; 15°…135° of it selected (typed: a
  // finger cannot hit 15° to the last bit) and dragged into the tab.
  ASSERT_TRUE(screen.tap("tab.0"));
  p.to_editor("tile.0.0");
  ASSERT_EQ(s.design().editor.waveform, design::detent_series().waveform) << p.said();
  screen.type("selectFrom", "15");
  screen.type("selectTo", "135");
  ASSERT_TRUE(screen.tap("select"));
  ASSERT_TRUE(screen.tap("tab.1"));
  drag(p.kiosk.window, centre(p.item("selectionChip")), [&] { return centre(p.item("tilePalette")); });
  ASSERT_EQ(s.design().palette[1].tiles.size(), 1u) << p.said();
  ASSERT_TRUE(screen.tap("tile.1.0"));
  screen.type("paletteName", "four clicks");
  ASSERT_TRUE(screen.tap("renameTile"));
  screen.shoot("prototyper-selection-1280x800");

  // The four clicks on −60°…60° (their span typed: nothing to snap to yet),
  // then the walls dropped beside them: each lands on the clicks' ends.
  p.place("tile.1.0", "line.position.new", "position", -1.0);
  ASSERT_EQ(s.design().lines(design::Channel::Position).lines.size(), 1u) << p.said();
  ASSERT_TRUE(screen.tap("placed.position/0/0"));
  screen.type("spanFrom", "-60");
  screen.type("spanTo", "60");
  ASSERT_TRUE(screen.tap("setSpan"));
  ASSERT_TRUE(screen.tap("tab.0"));
  p.place("tile.0.3", "line.position.0", "position", steps::kDetentsFrom - steps::kWall + 0.01);
  p.place("tile.0.2", "line.position.0", "position", steps::kDetentsTo + 0.01);
  ASSERT_EQ(s.design().lines(design::Channel::Position).lines[0].tiles.size(), 3u) << p.said();

  // Damping between the walls: dropped between −60° and 60°, it fills that gap.
  p.place("tile.0.4", "line.velocity.new", "velocity", 0.1);
  // Four times the damping: the template into the editor, all of it
  // selected, scaled ×4 against a horizontal mirror line at 0 (the factor
  // typed: a dragged point gives a factor to the pixel), made a tile.
  p.to_editor("tile.0.4");
  ASSERT_EQ(s.editorChannel(), "velocity");
  ASSERT_TRUE(screen.tap("selectAll"));
  ASSERT_TRUE(screen.tap("mirrorHorizontal"));
  screen.type("mirrorAt", "0");
  screen.type("scaleFactor", "4");
  ASSERT_TRUE(screen.tap("scaleSelection"));
  ASSERT_TRUE(screen.tap("tab.1"));
  drag(p.kiosk.window, centre(p.item("selectionChip")), [&] { return centre(p.item("tilePalette")); });
  ASSERT_EQ(s.design().palette[1].tiles.size(), 2u) << p.said();
  ASSERT_TRUE(screen.tap("tile.1.1"));
  screen.type("paletteName", "strong damping");
  ASSERT_TRUE(screen.tap("renameTile"));
  // …beyond Off and beyond Hi: each fills the gap between a wall's ends.
  p.place("tile.1.1", "line.velocity.0", "velocity", steps::kDetentsTo + 0.3);
  p.place("tile.1.1", "line.velocity.0", "velocity", steps::kDetentsFrom - 0.3);

  // The mass: dropped at the far end of one wall, then its other end
  // dragged to the far end of the other (Fig. 72's resize), landing there.
  ASSERT_TRUE(screen.tap("tab.0"));
  p.place("tile.0.6", "line.acceleration.new", "acceleration", steps::kRangeFrom + 0.01);
  QQuickItem* massEnd = p.item("placed.acceleration/0/0.to");
  ASSERT_NE(massEnd, nullptr) << p.said();
  drag_x(p.kiosk.window, centre(massEnd), p.pane_x("acceleration", steps::kRangeTo) - 2);
  screen.shoot("prototyper-fan-knob-built-1280x800");

  // Saved in the designs folder, a new design, the saved one opened again.
  ASSERT_TRUE(screen.tap("saveDesign"));
  ASSERT_TRUE(std::filesystem::exists(p.designs() / "fan-knob.json")) << p.said();
  ASSERT_TRUE(screen.tap("newDesign"));
  ASSERT_EQ(s.design(), design::new_design("untitled"));
  ASSERT_TRUE(screen.tap("openDesign"));
  ASSERT_TRUE(spin_until([&] { return screen.shows("design.fan-knob.json"); }, 5000));
  ASSERT_TRUE(screen.tap("design.fan-knob.json"));
  EXPECT_EQ(s.fileName(), "fan-knob.json");
  const design::Design thesis = steps::fan_knob();
  EXPECT_EQ(s.design(), thesis) << nlohmann::json::diff(design::to_json(thesis), design::to_json(s.design())).dump(1);
  EXPECT_EQ(design::read_design(p.designs() / "fan-knob.json"), thesis);
  EXPECT_TRUE(g_warnings.isEmpty()) << g_warnings.join("\n").toStdString();
}

TEST(Prototyper, UndoAndRedoFromTheScreensButtonsStepThroughTheEdits) {
  g_warnings.clear();
  Prototyper p;
  ASSERT_TRUE(p.daemon.ready()) << p.daemon.log();
  ASSERT_NE(p.kiosk.window, nullptr);
  const DesignSession& s = p.kiosk.designs;
  Screen& screen = p.screen;
  ASSERT_TRUE(spin_until([&] { return p.item("prototyperScreen") != nullptr; }, 10000));
  Screen::settle(p.item("prototyperScreen"));
  Screen::wait(300);
  EXPECT_FALSE(p.item("undo")->isEnabled());

  const design::Design fresh = s.design();
  p.to_editor("tile.0.1");  // the ramp
  const design::Design ramp = s.design();
  ASSERT_EQ(ramp.editor.waveform.points.size(), 5u) << p.said();
  // A tap on empty space of the editor adds a point there.
  QQuickItem* plot = p.item("editorPlot");
  QTest::mouseClick(p.kiosk.window, Qt::LeftButton, Qt::NoModifier,
                    plot->mapToScene(QPointF(plot->width() * 0.3, plot->height() * 0.2)).toPoint());
  Screen::wait(400);
  ASSERT_EQ(s.design().editor.waveform.points.size(), 6u) << p.said();
  const design::Design added = s.design();

  ASSERT_TRUE(screen.tap("undo"));
  EXPECT_EQ(s.design(), ramp);
  EXPECT_TRUE(screen.text("message").contains("added a point")) << screen.text("message").toStdString();
  ASSERT_TRUE(screen.tap("undo"));
  EXPECT_EQ(s.design(), fresh);
  EXPECT_FALSE(p.item("undo")->isEnabled());
  ASSERT_TRUE(screen.tap("redo"));
  EXPECT_EQ(s.design(), ramp);
  ASSERT_TRUE(screen.tap("redo"));
  EXPECT_EQ(s.design(), added);
  EXPECT_FALSE(p.item("redo")->isEnabled());
  // The points on screen are the design's.
  EXPECT_NE(p.item("point.5"), nullptr);
  EXPECT_TRUE(g_warnings.isEmpty()) << g_warnings.join("\n").toStdString();
}

TEST(Prototyper, AMalformedDesignOpenedIsNamedByItsKeyInTheMessageBarAndTheDesignOnScreenStays) {
  g_warnings.clear();
  Prototyper p;
  ASSERT_TRUE(p.daemon.ready()) << p.daemon.log();
  ASSERT_NE(p.kiosk.window, nullptr);
  const DesignSession& s = p.kiosk.designs;
  Screen& screen = p.screen;
  ASSERT_TRUE(spin_until([&] { return p.item("prototyperScreen") != nullptr; }, 10000));
  Screen::settle(p.item("prototyperScreen"));
  // A tile that ends before it starts.
  nlohmann::json j = design::to_json(steps::fan_knob());
  j["channels"]["position"]["lines"][0]["tiles"][1]["to"] = -2.0;
  std::filesystem::create_directories(p.designs());
  std::ofstream(p.designs() / "broken.json") << j.dump(2);

  p.to_editor("tile.0.0");
  const design::Design before = s.design();
  const int points = static_cast<int>(before.editor.waveform.points.size());
  ASSERT_TRUE(screen.tap("openDesign"));
  ASSERT_TRUE(spin_until([&] { return screen.shows("design.broken.json"); }, 5000));
  ASSERT_TRUE(screen.tap("design.broken.json"));
  const QString said = screen.text("message");
  EXPECT_TRUE(said.contains("broken.json: channels.position.lines[0].tiles[1].to: must be more than from"))
      << said.toStdString();
  EXPECT_EQ(s.design(), before);
  EXPECT_EQ(s.fileName(), "");
  // The editor still shows the same points.
  EXPECT_NE(p.item(("point." + std::to_string(points - 1)).c_str()), nullptr);
  screen.shoot("prototyper-malformed-1280x800");
}

TEST(Prototyper, PlaySendsTheDesignToHapticdWhichReportsItsTilesLoadedAndStopClearsThem) {
  g_warnings.clear();
  Prototyper p;
  ASSERT_TRUE(p.daemon.ready()) << p.daemon.log();
  ASSERT_NE(p.kiosk.window, nullptr);
  DesignSession& s = p.kiosk.designs;
  Screen& screen = p.screen;
  ASSERT_TRUE(spin_until([&] { return p.kiosk.link.connected(); })) << p.daemon.log();
  std::filesystem::create_directories(p.designs());
  design::write_design(p.designs() / "fan-knob.json", steps::fan_knob());
  ASSERT_TRUE(s.open("fan-knob.json"));
  const nlohmann::json args = design::load_tiles_args(s.design());
  const auto sent = static_cast<int>(args.value("position", nlohmann::json::array()).size());
  ASSERT_GT(sent, 0);

  ASSERT_TRUE(screen.tap("play"));
  const auto loaded = [&] {
    const QVariantMap state = p.kiosk.link.state();
    return state.value("tiles").toMap().value("position").toInt();
  };
  ASSERT_TRUE(spin_until([&] { return s.playing() && p.kiosk.link.mode() == "render" && loaded() == sent; }, 20000))
      << p.said() << " tiles " << loaded() << " of " << sent << "; " << p.daemon.log();
  EXPECT_EQ(screen.text("play"), "■ Stop");
  // An edit while playing is sent again: one tile fewer (an active line off).
  ASSERT_TRUE(screen.tap("active.acceleration.0"));
  ASSERT_TRUE(spin_until([&] { return loaded() == sent - 1; }, 20000)) << p.said();
  EXPECT_TRUE(s.playing());
  ASSERT_TRUE(screen.tap("play"));
  ASSERT_TRUE(spin_until([&] { return !s.playing() && p.kiosk.link.mode() == "idle" && loaded() == 0; }, 20000))
      << p.said();
  EXPECT_TRUE(g_warnings.isEmpty()) << g_warnings.join("\n").toStdString();
}

}  // namespace
}  // namespace knoblab::ui
