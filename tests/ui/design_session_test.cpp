// The prototyper's session without a screen: where dropped tiles land (the
// snapping that lets a finger build the exact design), refused edits and
// files said in the message bar with nothing changed, save and reopen.
#include <gtest/gtest.h>

#include <QSignalSpy>

#include <filesystem>
#include <fstream>

#include "daemon_link.hpp"
#include "design_session.hpp"
#include "knoblab/design/design_json.hpp"
#include "knoblab/design/templates.hpp"
#include "pane_snap.hpp"
#include "process.hpp"

namespace knoblab::ui {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

TEST(PaneSnap, AnEndLetGoNearAnotherTilesEndLandsOnItBitForBit) {
  const double edge = -60 * kDeg;
  const std::vector<double> edges{edge, 60 * kDeg};
  // The end, a little past the edge, snaps; the start follows by the length.
  const PaneSpan end = snap_span(edge - 0.6 + 0.01, 0.6, edges, 0.02);
  EXPECT_EQ(end.to, edge);
  EXPECT_EQ(end.from, edge - 0.6);
  // The start snaps; the end is start + length.
  const PaneSpan start = snap_span(60 * kDeg - 0.015, 0.6, edges, 0.02);
  EXPECT_EQ(start.from, 60 * kDeg);
  EXPECT_EQ(start.to, 60 * kDeg + 0.6);
  // Too far from any edge: where it was let go.
  const PaneSpan free = snap_span(0.3, 0.2, edges, 0.02);
  EXPECT_EQ(free.from, 0.3);
  EXPECT_EQ(snap_edge(1.0, edges, 0.02), 1.0);
  EXPECT_EQ(snap_edge(60 * kDeg + 0.01, edges, 0.02), 60 * kDeg);
}

TEST(PaneSnap, AVelocityTileFillsTheGapBetweenTheTileEndsAroundWhereItIsDropped) {
  const std::vector<double> edges{-1.0, -0.5, 0.5, 1.0};
  EXPECT_EQ(fill_gap(0.1, edges, 2.0).from, -0.5);
  EXPECT_EQ(fill_gap(0.1, edges, 2.0).to, 0.5);
  EXPECT_EQ(fill_gap(0.7, edges, 2.0).from, 0.5);
  EXPECT_EQ(fill_gap(0.7, edges, 2.0).to, 1.0);
  // Beyond the last end: half the fallback on the open side.
  EXPECT_EQ(fill_gap(2.0, edges, 1.0).from, 1.0);
  EXPECT_EQ(fill_gap(2.0, edges, 1.0).to, 2.5);
}

LinkWorker::Options nowhere(const test::ScratchDir& dir) {
  LinkWorker::Options o;
  o.socket = QString::fromStdString((dir / "nobody.sock").string());
  return o;
}

TEST(DesignSession, ARefusedEditSaysItsSentenceInTheMessageBarAndChangesNothing) {
  test::ScratchDir dir;
  DaemonLink link(nowhere(dir));
  DesignSession session(&link, {.designsDir = QString::fromStdString((dir / "designs").string())});
  QSignalSpy messages(&session, &DesignSession::message);
  const design::Design before = session.design();
  EXPECT_FALSE(session.removePoint(0));  // the editor is empty
  ASSERT_EQ(messages.size(), 1);
  EXPECT_EQ(messages[0][0].toString(), "The editor is empty: drag a tile or a template into it first.");
  EXPECT_EQ(session.design(), before);
  EXPECT_FALSE(session.canUndo());
  // An edit that applies is one undoable step with its label.
  EXPECT_TRUE(session.editTile(0, 0));
  EXPECT_TRUE(session.canUndo());
  EXPECT_EQ(session.undoLabel(), "tile into the editor");
  session.undo();
  EXPECT_EQ(session.design(), before);
}

TEST(DesignSession, AFileThatIsNotADesignIsNamedByItsKeyAndTheDesignStaysAsItWas) {
  test::ScratchDir dir;
  const std::filesystem::path designs = dir / "designs";
  std::filesystem::create_directories(designs);
  nlohmann::json j = design::to_json(design::new_design("x"));
  j["palette"][0]["tiles"][1]["waveform"]["x"] = "many";
  std::ofstream(designs / "bad.json") << j.dump(2);
  DaemonLink link(nowhere(dir));
  DesignSession session(&link, {.designsDir = QString::fromStdString(designs.string())});
  ASSERT_TRUE(session.editTile(0, 0));
  const design::Design before = session.design();
  const int revision = session.revision();
  QSignalSpy messages(&session, &DesignSession::message);
  EXPECT_FALSE(session.open("bad.json"));
  ASSERT_EQ(messages.size(), 1);
  EXPECT_NE(messages[0][0].toString().indexOf("palette[0].tiles[1].waveform.x"), -1) << messages[0][0].toString().toStdString();
  EXPECT_EQ(messages[0][1].toString(), "error");
  EXPECT_EQ(session.design(), before);
  EXPECT_EQ(session.revision(), revision);
  EXPECT_TRUE(session.canUndo());  // the history is kept too
}

TEST(DesignSession, ADesignSavedInTheLibraryFolderOpensAsItWas) {
  test::ScratchDir dir;
  const std::filesystem::path designs = dir / "designs";
  DaemonLink link(nowhere(dir));
  DesignSession session(&link, {.designsDir = QString::fromStdString(designs.string())});
  ASSERT_TRUE(session.renameDesign("my knob"));
  ASSERT_TRUE(session.placeTileAt("position", 0, 0, 1, -0.5, 0.25));
  EXPECT_TRUE(session.modified());
  ASSERT_TRUE(session.save());
  EXPECT_FALSE(session.modified());
  EXPECT_EQ(session.fileName(), "my-knob.json");
  EXPECT_TRUE(std::filesystem::exists(designs / "my-knob.json"));
  EXPECT_EQ(session.designFiles(), QStringList{"my-knob.json"});
  const design::Design saved = session.design();
  session.newDesign();
  EXPECT_NE(session.design(), saved);
  ASSERT_TRUE(session.open("my-knob.json"));
  EXPECT_EQ(session.design(), saved);
  EXPECT_FALSE(session.canUndo());
}

}  // namespace
}  // namespace knoblab::ui
