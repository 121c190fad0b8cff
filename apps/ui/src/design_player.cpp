#include "design_player.hpp"

#include <QByteArray>
#include <QJsonDocument>
#include <QJsonObject>

#include "daemon_link.hpp"

namespace knoblab::ui {

DesignPlayer::DesignPlayer(DaemonLink* link, QObject* parent) : QObject(parent), link_(link) {
  connect(link_, &DaemonLink::replied, this,
          [this](int token, const QString& cmd, bool ok, const QVariantMap&, const QString& error) {
            on_replied(token, cmd, ok, error);
          });
  connect(link_, &DaemonLink::stateChanged, this, &DesignPlayer::on_state);
}

QVariantMap DesignPlayer::to_variant(const nlohmann::json& args) {
  // JSON text both ways: nlohmann writes the shortest digits that read back
  // as the same double, so the knob gets the design's numbers exactly.
  return QJsonDocument::fromJson(QByteArray::fromStdString(args.dump())).object().toVariantMap();
}

void DesignPlayer::play(const nlohmann::json& args) {
  seen_render_ = false;
  start_token_ = link_->request(QStringLiteral("load_tiles"), to_variant(args));
}

void DesignPlayer::update(const nlohmann::json& args) {
  if (playing_) update_token_ = link_->request(QStringLiteral("load_tiles"), to_variant(args));
}

void DesignPlayer::stop() {
  start_token_ = mode_token_ = update_token_ = 0;
  link_->request(QStringLiteral("set_mode"), {{QStringLiteral("mode"), QStringLiteral("idle")}});
  link_->request(QStringLiteral("load_tiles"), {});
  set_playing(false);
}

void DesignPlayer::on_replied(int token, const QString& cmd, bool ok, const QString& error) {
  Q_UNUSED(cmd);
  if (token == 0) return;
  if (token == start_token_) {
    start_token_ = 0;
    if (!ok) {
      emit message(QStringLiteral("hapticd would not play the design: ") + error, QStringLiteral("warning"));
      return;
    }
    mode_token_ = link_->request(QStringLiteral("set_mode"), {{QStringLiteral("mode"), QStringLiteral("render")}});
  } else if (token == mode_token_) {
    mode_token_ = 0;
    if (!ok) {
      emit message(QStringLiteral("hapticd would not render: ") + error, QStringLiteral("warning"));
      return;
    }
    set_playing(true);
  } else if (token == update_token_) {
    update_token_ = 0;
    if (!ok)
      emit message(QStringLiteral("hapticd kept the design as it was before this change: ") + error,
                   QStringLiteral("warning"));
  }
}

// A fault, the e-stop or another client ends render mode: then nothing plays.
void DesignPlayer::on_state() {
  if (!playing_) return;
  const bool render = link_->mode() == QStringLiteral("render");
  if (render) seen_render_ = true;
  else if (seen_render_) {
    set_playing(false);
    emit message(QStringLiteral("hapticd left render mode: the design stopped playing"), QStringLiteral("warning"));
  }
}

void DesignPlayer::set_playing(bool on) {
  if (on == playing_) return;
  playing_ = on;
  emit playingChanged();
}

}  // namespace knoblab::ui
