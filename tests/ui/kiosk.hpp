// The kiosk as knoblab-ui builds it, for the tests that drive its real
// screens offscreen by touch (wizard_test.cpp, study_person_test.cpp): the
// window with its C++ objects, finding items by objectName, tapping and
// typing as a person would, and the warnings Qt and QML print meanwhile.
#pragma once

#include <gtest/gtest.h>

#include <QQmlApplicationEngine>
#include <QQuickItem>
#include <QQuickWindow>
#include <QTest>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>

#include "daemon_link.hpp"
#include "design_session.hpp"
#include "event_loop.hpp"
#include "hapticd_process.hpp"
#include "job_runner.hpp"
#include "knob_library.hpp"
#include "screen_check.hpp"
#include "study_session.hpp"
#include "telemetry_feed.hpp"

namespace knoblab::ui {

// Every warning Qt and QML print while the test runs: there must be none.
inline QStringList g_warnings;
inline void keep_warnings(QtMsgType type, const QMessageLogContext&, const QString& text) {
  if (type != QtDebugMsg && type != QtInfoMsg) g_warnings << text;
}

inline bool spin_until(const std::function<bool()>& done, int ms = 60000) { return test_loop::spin_until(done, ms); }

// The visible item with this objectName, searched through the visual tree.
inline QQuickItem* find(QQuickItem* root, const QString& name) {
  if (!root || !root->isVisible()) return nullptr;
  if (root->objectName() == name) return root;
  for (QQuickItem* child : root->childItems())
    if (QQuickItem* hit = find(child, name)) return hit;
  return nullptr;
}

// A key of the on-screen keyboard by its label (Qt Virtual Keyboard's keys
// have no object names; they carry their letter as `text`).
inline QQuickItem* find_key(QQuickItem* root, const QString& label) {
  if (!root || !root->isVisible()) return nullptr;
  if (QString(root->metaObject()->className()).contains(QStringLiteral("Key")) &&
      root->property("text").toString() == label && root->width() > 0)
    return root;
  for (QQuickItem* child : root->childItems())
    if (QQuickItem* hit = find_key(child, label)) return hit;
  return nullptr;
}

class Screen {
 public:
  explicit Screen(QQuickWindow* w) : window_(w) {}
  QQuickItem* item(const QString& name) const { return find(window_->contentItem(), name); }
  bool shows(const QString& name) const { return item(name) != nullptr; }
  QString text(const QString& name) const {
    const QQuickItem* i = item(name);
    return i ? i->property("text").toString() : QString();
  }
  // A finger on the item's centre (TapHandlers take a mouse click as a tap),
  // once it has stopped moving (a screen slides in), then the screen let
  // settle as a person would look before the next tap.
  bool tap(const QString& name) const {
    QQuickItem* i = item(name);
    if (!i || !i->isEnabled()) return false;
    scroll_to(i);
    QPointF c = i->mapToScene(QPointF(i->width() / 2, i->height() / 2));
    for (QPointF before; before != c;) {
      before = c;
      wait(100);
      if (!(i = item(name))) return false;
      c = i->mapToScene(QPointF(i->width() / 2, i->height() / 2));
    }
    QTest::mouseClick(window_, Qt::LeftButton, Qt::NoModifier, c.toPoint());
    wait(300);
    return true;
  }
  // A StackView takes no input while a screen slides in (a tap then is
  // lost), and its animators set the item's position only when they end:
  // waits for the slide.
  static void settle(QQuickItem* i) {
    for (QQuickItem* p = i->parentItem(); p; p = p->parentItem())
      if (p->inherits("QQuickStackView")) spin_until([&] { return !p->property("busy").toBool(); }, 10000);
  }
  // As a finger would flick: a scrolling parent moved until the item is on screen.
  void scroll_to(QQuickItem* i) const {
    for (QQuickItem* p = i->parentItem(); p; p = p->parentItem()) {
      if (!p->inherits("QQuickFlickable")) continue;
      const QRectF box = i->mapRectToItem(p, QRectF(0, 0, i->width(), i->height()));
      const qreal y = p->property("contentY").toReal();
      // Within the content's bounds: beyond them the flickable springs back,
      // and a press while it moves only stops it.
      const qreal top = 0, bottom = std::max<qreal>(0, p->property("contentHeight").toReal() - p->height());
      if (box.bottom() > p->height()) p->setProperty("contentY", std::clamp<qreal>(y + box.bottom() - p->height() + 10, top, bottom));
      else if (box.top() < 0) p->setProperty("contentY", std::clamp<qreal>(y + box.top() - 10, top, bottom));
      spin_until([&] { return !p->property("moving").toBool(); }, 5000);
      wait(100);
      return;
    }
  }
  static void wait(int ms) { test_loop::run_for(ms); }
  // The screen as it is now, kept in build/ui-screens; no text on it cut.
  void shoot(const std::string& name) const {
    std::filesystem::create_directories(KNOBLAB_UI_SCREENS_DIR);
    const QImage image = window_->grabWindow();
    EXPECT_TRUE(drawn(image)) << name;
    image.save(QString::fromStdString(std::string(KNOBLAB_UI_SCREENS_DIR) + "/" + name + ".png"));
    const QStringList clipped = clipped_texts(window_->contentItem());
    EXPECT_TRUE(clipped.isEmpty()) << name << ": " << clipped.join("; ").toStdString();
  }
  void type(const QString& name, const QString& text) const {
    if (QQuickItem* i = item(name + ".input")) i->setProperty("text", text);
  }
  // Letters typed on the on-screen keyboard, key by key; false when a key is missing.
  bool type_on_keyboard(const QString& letters) const {
    for (const QChar c : letters) {
      QQuickItem* key = find_key(window_->contentItem(), QString(c));
      if (!key) return false;
      const QPointF at = key->mapToScene(QPointF(key->width() / 2, key->height() / 2));
      QTest::mouseClick(window_, Qt::LeftButton, Qt::NoModifier, at.toPoint());
      wait(150);
    }
    return true;
  }

 private:
  QQuickWindow* window_;
};

// The kiosk as knoblab-ui builds it, against `daemon`, offscreen at `panel`,
// opened at `start`, offering the study protocols in `studies` and keeping
// the prototyper's designs in `designs_dir` (default: the daemon's scratch
// directory); what it put in the message bar kept in `messages`.
struct Kiosk {
  Kiosk(const test::Hapticd& daemon, const QString& start, QSize panel, const QString& studies = {},
        const QString& designs_dir = {})
      : link(options(daemon)),
        knobs(QString::fromStdString(daemon.db())),
        jobs(KNOBLAB_CLI_PATH, QString::fromStdString(daemon.db())),
        study({.db = QString::fromStdString(daemon.db()), .socket = QString::fromStdString(daemon.socket()),
               .studiesDir = studies, .simulate = false, .pause_at = {}}),
        designs(&link, {.designsDir = designs_dir.isEmpty() ? QString::fromStdString(daemon.dir() + "/designs")
                                                            : designs_dir}) {
    QObject::connect(&link, &DaemonLink::telemetryNameChanged, &feed, [this] { feed.setRing(link.telemetryName()); });
    QObject::connect(&link, &DaemonLink::message, [this](const QString& t, const QString&) { messages << t; });
    QObject::connect(&study, qOverload<const QString&, const QString&>(&StudySession::message),
                     [this](const QString& t, const QString&) { messages << t; });
    QObject::connect(&designs, &DesignSession::message, [this](const QString& t, const QString&) { messages << t; });
    engine.setInitialProperties({{"link", QVariant::fromValue(&link)},
                                 {"knobs", QVariant::fromValue(&knobs)},
                                 {"jobs", QVariant::fromValue(&jobs)},
                                 {"feed", QVariant::fromValue(&feed)},
                                 {"study", QVariant::fromValue(&study)},
                                 {"designs", QVariant::fromValue(&designs)},
                                 {"startScreen", start},
                                 {"width", panel.width()},
                                 {"height", panel.height()}});
    engine.loadFromModule("Knoblab.Ui", "Main");
    if (!engine.rootObjects().isEmpty()) window = qobject_cast<QQuickWindow*>(engine.rootObjects().first());
    if (window) window->show();
  }
  static LinkWorker::Options options(const test::Hapticd& daemon) {
    LinkWorker::Options o;
    o.socket = QString::fromStdString(daemon.socket());
    return o;
  }

  DaemonLink link;
  KnobLibrary knobs;
  JobRunner jobs;
  TelemetryFeed feed;
  StudySession study;
  DesignSession designs;
  QStringList messages;
  QQmlApplicationEngine engine;
  QQuickWindow* window = nullptr;  // null: Main did not load
};

}  // namespace knoblab::ui
