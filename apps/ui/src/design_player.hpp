// Plays a design on the knob, through hapticd only (the DaemonLink): its
// render model as `load_tiles`, then render mode. While it plays, a changed
// design is sent again as a whole set; hapticd cross-fades from the old set
// to the new, so an edit is felt at once and without a step. A set hapticd
// refuses (beyond the torque limit or the loop's stability bound) is said in
// the message bar with hapticd's reason, and the knob keeps what it had.
#pragma once

#include <QObject>
#include <QString>
#include <QVariantMap>

#include <nlohmann/json.hpp>

namespace knoblab::ui {

class DaemonLink;

class DesignPlayer : public QObject {
  Q_OBJECT

 public:
  explicit DesignPlayer(DaemonLink* link, QObject* parent = nullptr);

  bool playing() const { return playing_; }
  // load_tiles with `args`, then set_mode render once hapticd took them.
  void play(const nlohmann::json& args);
  // While playing: the changed design's tiles (nothing otherwise).
  void update(const nlohmann::json& args);
  // Render mode off and the tiles cleared, so a later render (the library's
  // "Feel it") is not summed with a design left behind.
  void stop();

  // load_tiles' arguments as DaemonLink::request takes them.
  static QVariantMap to_variant(const nlohmann::json& args);

 signals:
  void playingChanged();
  void message(const QString& text, const QString& level);

 private:
  void on_replied(int token, const QString& cmd, bool ok, const QString& error);
  void on_state();
  void set_playing(bool on);

  DaemonLink* link_;
  bool playing_ = false;
  bool seen_render_ = false;  // hapticd has reported render mode since play
  int start_token_ = 0;       // the load_tiles that starts playing
  int update_token_ = 0;      // the latest load_tiles sent while playing
  int mode_token_ = 0;        // set_mode render
};

}  // namespace knoblab::ui
