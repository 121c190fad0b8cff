// The Haptic Icon Prototyper's design as the screen sees it (thesis ch. 5):
// the waveform editor's points, the tile palette, the tile pane, undo and
// redo, the file, and playing it on the knob. It wraps design::History, so
// every edit is one undoable step with a short label; an edit the design
// refuses (design::EditError) is said in the message bar as its sentence
// and changes nothing (§5.4: notification, not dialogs).
//
// Numbers cross in SI (rad, rad/s, s, N·m, kg·m²): the screen converts to
// degrees and mN·m where it shows them (design.mjs).
#pragma once

#include <QObject>
#include <QString>
#include <QStringList>
#include <QVariantList>
#include <QtQml/qqmlregistration.h>

#include <filesystem>
#include <limits>

#include "design_player.hpp"
#include "knoblab/design/history.hpp"

namespace knoblab::ui {

class DaemonLink;

class DesignSession : public QObject {
  Q_OBJECT
  QML_ELEMENT
  QML_UNCREATABLE("knoblab-ui makes the one design session")
  Q_PROPERTY(QString name READ name NOTIFY designChanged)
  // The file it was opened from or saved to ("" for a new design), and its
  // name without the folder.
  Q_PROPERTY(QString filePath READ filePath NOTIFY fileChanged)
  Q_PROPERTY(QString fileName READ fileName NOTIFY fileChanged)
  // Where designs are kept (--designs), and the designs there (file names).
  Q_PROPERTY(QString designsDir READ designsDir CONSTANT)
  Q_PROPERTY(QStringList designFiles READ designFiles NOTIFY filesChanged)
  Q_PROPERTY(bool modified READ modified NOTIFY designChanged)
  Q_PROPERTY(bool canUndo READ canUndo NOTIFY designChanged)
  Q_PROPERTY(bool canRedo READ canRedo NOTIFY designChanged)
  Q_PROPERTY(QString undoLabel READ undoLabel NOTIFY designChanged)
  Q_PROPERTY(QString redoLabel READ redoLabel NOTIFY designChanged)
  // The editor: what its waveform is drawn for (a channel name: its axes) and its points [{x, y}].
  Q_PROPERTY(QString editorChannel READ editorChannel NOTIFY designChanged)
  Q_PROPERTY(QVariantList editorPoints READ editorPoints NOTIFY designChanged)
  // [{name, tiles: [{name, drawnFor, peak, thumb}]}] (design_variant.hpp).
  Q_PROPERTY(QVariantList palette READ palette NOTIFY designChanged)
  // [{name, play, lines: [{active, tiles: [{name, drawnFor, from, to, peak, thumb}]}]}].
  Q_PROPERTY(QVariantList channels READ channels NOTIFY designChanged)
  Q_PROPERTY(bool timeLoop READ timeLoop NOTIFY designChanged)
  // Counts edits, undos and opens: a test's way to see that one happened.
  Q_PROPERTY(int revision READ revision NOTIFY designChanged)
  Q_PROPERTY(bool playing READ playing NOTIFY playingChanged)
  // hapticd's torque limit (N·m): get_state's torque_limit_Nm when it says, else the default 0.18.
  Q_PROPERTY(double torqueLimit READ torqueLimit NOTIFY limitsChanged)
  // The loop's stability bound at hapticd's rate (stability_bound.hpp): the
  // most damping (N·m·s/rad) and stiffness (N·m/rad) it renders stably; NaN
  // until hapticd has said its rate.
  Q_PROPERTY(double maxDamping READ maxDamping NOTIFY limitsChanged)
  Q_PROPERTY(double maxStiffness READ maxStiffness NOTIFY limitsChanged)

 public:
  struct Options {
    QString designsDir = QStringLiteral("/var/lib/knoblab/designs");
  };
  DesignSession(DaemonLink* link, Options options, QObject* parent = nullptr);

  const design::Design& design() const { return history_.design(); }
  QString name() const { return QString::fromStdString(design().name); }
  QString filePath() const { return QString::fromStdString(file_.string()); }
  QString fileName() const { return QString::fromStdString(file_.filename().string()); }
  QString designsDir() const { return QString::fromStdString(dir_.string()); }
  QStringList designFiles() const { return files_; }
  bool modified() const { return history_.modified(); }
  bool canUndo() const { return history_.can_undo(); }
  bool canRedo() const { return history_.can_redo(); }
  QString undoLabel() const { return QString::fromStdString(history_.undo_label()); }
  QString redoLabel() const { return QString::fromStdString(history_.redo_label()); }
  QString editorChannel() const;
  QVariantList editorPoints() const { return editor_points_; }
  QVariantList palette() const { return palette_; }
  QVariantList channels() const { return channels_; }
  bool timeLoop() const { return design().time_loop; }
  int revision() const { return revision_; }
  bool playing() const { return player_.playing(); }
  double torqueLimit() const { return torque_limit_; }
  double maxDamping() const { return max_damping_; }
  double maxStiffness() const { return max_stiffness_; }

  // The editor's curve as played, sampled over [from, to] ([{x, y}]).
  Q_INVOKABLE QVariantList editorCurve(double from, double to, int samples) const;

  // The editor (§5.3.1).
  Q_INVOKABLE bool editTile(int tab, int index);
  Q_INVOKABLE bool movePoint(int index, double x, double y);
  Q_INVOKABLE bool addPoint(double x, double y);
  Q_INVOKABLE bool removePoint(int index);
  Q_INVOKABLE bool scaleSelection(double from, double to, bool horizontal, double at, double factor);
  // The selection [from, to] as a new tile of `tab` called `name` (the next
  // free "tile N" when empty).
  Q_INVOKABLE bool tileFromSelection(double from, double to, int tab, const QString& name = {});

  // The palette.
  Q_INVOKABLE bool addTab(const QString& name);
  Q_INVOKABLE bool renameTab(int tab, const QString& name);
  Q_INVOKABLE bool removeTab(int tab);
  Q_INVOKABLE bool renameTile(int tab, int index, const QString& name);
  Q_INVOKABLE bool removeTile(int tab, int index);

  // The pane. A palette tile dropped at `from` in `channel`'s line `line`
  // (one past the last starts a new line): its length is the tile's own
  // span where that is an angle (or a time) on this channel's axis, else a
  // quarter turn (1 s in time); an end within `snap` of another tile's end
  // lands on it exactly. A velocity tile instead fills the gap between the
  // tile ends either side of `from` (pane_snap.hpp).
  Q_INVOKABLE bool placeTile(const QString& channel, int line, int tab, int index, double from, double snap);
  Q_INVOKABLE bool placeTileAt(const QString& channel, int line, int tab, int index, double from, double to);
  Q_INVOKABLE bool moveTile(const QString& channel, int line, int index, double from, double snap);
  // One end dragged (`end` "from" or "to"), snapping as above.
  Q_INVOKABLE bool resizeTileEnd(const QString& channel, int line, int index, const QString& end, double at,
                                 double snap);
  Q_INVOKABLE bool resizeTile(const QString& channel, int line, int index, double from, double to);
  Q_INVOKABLE bool removePlaced(const QString& channel, int line, int index);
  Q_INVOKABLE bool superimpose(const QString& channel, int lineA, int indexA, int lineB, int indexB);
  Q_INVOKABLE bool addLine(const QString& channel);
  Q_INVOKABLE bool removeLine(const QString& channel, int line);
  Q_INVOKABLE bool setLineActive(const QString& channel, int line, bool active);
  Q_INVOKABLE bool setChannelPlay(const QString& channel, bool play);
  Q_INVOKABLE bool setTimeLoop(bool loop);
  Q_INVOKABLE bool renameDesign(const QString& name);

  Q_INVOKABLE void undo();
  Q_INVOKABLE void redo();
  // A new design with the templates tab (one undoable step; the file is forgotten).
  Q_INVOKABLE void newDesign(const QString& name = QStringLiteral("untitled"));
  // `path` absolute, or a file name in designsDir. A file that is not a
  // design leaves the current one as it was and says why, naming the key.
  // `announce`: say "Opened …" (not for the one opened at start).
  Q_INVOKABLE bool open(const QString& path, bool announce = true);
  // To `path` (as open), or the current file, or "<name>.json" in designsDir.
  Q_INVOKABLE bool save(const QString& path = {});
  Q_INVOKABLE void refreshFiles();

  // Plays the design's active lines of the channels that play (load_tiles,
  // then render mode); every edit while playing is sent again.
  Q_INVOKABLE void play();
  Q_INVOKABLE void stop();

 signals:
  void designChanged();
  void fileChanged();
  void filesChanged();
  void playingChanged();
  void limitsChanged();
  // For the message bar: level "info", "warning" or "error".
  void message(const QString& text, const QString& level);

 private:
  template <class Edit>
  bool edit(const QString& label, Edit&& e);
  void changed();
  std::filesystem::path resolve(const QString& path) const;
  void read_limits();

  DaemonLink* link_;
  std::filesystem::path dir_, file_;
  design::History history_;
  DesignPlayer player_;
  QVariantList editor_points_, palette_, channels_;
  QStringList files_;
  int revision_ = 0;
  double torque_limit_ = 0.18;
  double rate_hz_ = 0.0;
  double max_damping_ = std::numeric_limits<double>::quiet_NaN();
  double max_stiffness_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace knoblab::ui
