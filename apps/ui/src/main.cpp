// knoblab-ui: the touchscreen front-end. Full screen on the appliance
// (eglfs or linuxfb, chosen by QT_QPA_PLATFORM), windowed on a desktop, or
// offscreen for --screenshot.
#include <QGuiApplication>
#include <QQmlApplicationEngine>
#include <QQuickItem>
#include <QQuickWindow>
#include <QTimer>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "daemon_link.hpp"
#include "design_session.hpp"
#include "job_runner.hpp"
#include "knob_library.hpp"
#include "study_session.hpp"
#include "telemetry_feed.hpp"
#include "knoblab/version.hpp"
#include "screen_check.hpp"
#include "ui_options.hpp"

namespace {

using knoblab::ui::UiOptions;

// Every QML warning is a defect the screenshot run reports (and fails on).
QStringList g_warnings;
QtMessageHandler g_previous = nullptr;

void keep_warnings(QtMsgType type, const QMessageLogContext& context, const QString& text) {
  if (type == QtWarningMsg || type == QtCriticalMsg || type == QtFatalMsg) g_warnings << text;
  if (g_previous) g_previous(type, context, text);
}

// Renders the window once hapticd's state is in and the library and any
// job the screen started are done (or the wait is over), writes the PNG and
// checks it. Exit status: 0 all well, 1 a problem.
int screenshot(QQuickWindow& window, knoblab::ui::DaemonLink& link, const knoblab::ui::KnobLibrary& library,
               const knoblab::ui::JobRunner& jobs, const knoblab::ui::StudySession& study, const UiOptions& o) {
  QElapsedTimer waited;
  waited.start();
  // A simulated study session runs until it pauses where it was asked to.
  while ((!link.stateKnown() || library.loading() || jobs.running() || study.settling()) &&
         waited.elapsed() < static_cast<qint64>(o.wait_s * 1000))
    QCoreApplication::processEvents(QEventLoop::AllEvents, 50);
  // Let bindings settle and animations (the message bar's) finish.
  QElapsedTimer settle;
  settle.start();
  while (settle.elapsed() < 600) QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
  const QImage image = window.grabWindow();
  int status = 0;
  if (!image.save(QString::fromStdString(o.screenshot))) {
    std::fprintf(stderr, "knoblab-ui: cannot write %s\n", o.screenshot.c_str());
    return 2;
  }
  if (!knoblab::ui::drawn(image)) {
    std::fprintf(stderr, "knoblab-ui: %s is blank\n", o.screenshot.c_str());
    status = 1;
  }
  for (const QString& p : knoblab::ui::clipped_texts(window.contentItem())) {
    std::fprintf(stderr, "knoblab-ui: clipped text: %s\n", qPrintable(p));
    status = 1;
  }
  for (const QString& w : g_warnings) {
    std::fprintf(stderr, "knoblab-ui: warning: %s\n", qPrintable(w));
    status = 1;
  }
  for (const QString& line : knoblab::ui::named_texts(window.contentItem())) std::printf("%s\n", qPrintable(line));
  // The PNG is written all the same: it shows what the kiosk shows then.
  if (!link.stateKnown()) {
    std::fprintf(stderr, "knoblab-ui: no state from hapticd within %g s\n", o.wait_s);
    status = 1;
  }
  if (study.settling()) {
    std::fprintf(stderr, "knoblab-ui: the study session did not reach %s within %g s\n", o.study_pause_at.c_str(),
                 o.wait_s);
    status = 1;
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  UiOptions o;
  try {
    o = knoblab::ui::parse_ui_options(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "knoblab-ui: %s\n%s", e.what(), knoblab::ui::ui_usage().c_str());
    return 2;
  }
  if (o.help) {
    std::printf("%s", knoblab::ui::ui_usage().c_str());
    return 0;
  }
  if (o.version) {
    std::printf("knoblab-ui %s\n", knoblab::kVersion);
    return 0;
  }
  if (!o.screenshot.empty()) {
    // Offscreen, drawn by the software renderer: the same pixels on any machine.
    qputenv("QT_QPA_PLATFORM", "offscreen");
    qputenv("QT_QUICK_BACKEND", "software");
  }
  // The on-screen keyboard is the app's own (InputPanel in Main.qml), on a
  // desktop too; QT_IM_MODULE set by the user wins.
  if (!qEnvironmentVariableIsSet("QT_IM_MODULE")) qputenv("QT_IM_MODULE", "qtvirtualkeyboard");
  g_previous = qInstallMessageHandler(keep_warnings);
  QGuiApplication app(argc, argv);
  app.setApplicationName(QStringLiteral("knoblab-ui"));

  knoblab::ui::LinkWorker::Options lo;
  lo.socket = QString::fromStdString(o.socket);
  lo.supervise = o.supervise && o.screenshot.empty();
  knoblab::ui::DaemonLink link(lo);
  knoblab::ui::KnobLibrary library(QString::fromStdString(o.db));
  knoblab::ui::JobRunner jobs(QString::fromStdString(o.knoblab), QString::fromStdString(o.db));
  knoblab::ui::TelemetryFeed feed;
  knoblab::ui::StudySession study({.db = QString::fromStdString(o.db),
                                   .socket = QString::fromStdString(o.socket),
                                   .studiesDir = QString::fromStdString(o.studies),
                                   .simulate = o.study_simulate,
                                   .pause_at = QString::fromStdString(o.study_pause_at)});
  knoblab::ui::DesignSession designs(&link, {.designsDir = QString::fromStdString(o.designs)});
  QObject::connect(&link, &knoblab::ui::DaemonLink::telemetryNameChanged, &feed,
                   [&] { feed.setRing(link.telemetryName()); });

  QQmlApplicationEngine engine;
  engine.setInitialProperties({{QStringLiteral("link"), QVariant::fromValue(&link)},
                               {QStringLiteral("knobs"), QVariant::fromValue(&library)},
                               {QStringLiteral("jobs"), QVariant::fromValue(&jobs)},
                               {QStringLiteral("feed"), QVariant::fromValue(&feed)},
                               {QStringLiteral("study"), QVariant::fromValue(&study)},
                               {QStringLiteral("designs"), QVariant::fromValue(&designs)},
                               {QStringLiteral("startScreen"), QString::fromStdString(o.screen)},
                               {QStringLiteral("width"), o.width},
                               {QStringLiteral("height"), o.height}});
  QObject::connect(&engine, &QQmlApplicationEngine::objectCreationFailed, &app, [] { QCoreApplication::exit(2); },
                   Qt::QueuedConnection);
  engine.loadFromModule("Knoblab.Ui", "Main");
  if (engine.rootObjects().isEmpty()) return 2;
  auto* window = qobject_cast<QQuickWindow*>(engine.rootObjects().first());
  if (!window) return 2;
  // The screens are Main.qml's: a name it does not know is a bad option.
  const QStringList screens = QStringList{QStringLiteral("home")} + window->property("screens").toMap().keys();
  if (!screens.contains(QString::fromStdString(o.screen))) {
    std::fprintf(stderr, "knoblab-ui: --screen: no screen called %s (screens: %s)\n", o.screen.c_str(),
                 qPrintable(screens.join(QStringLiteral(", "))));
    return 2;
  }
  // Opened before the first frame, so a screenshot shows it (or why not, in the message bar).
  if (!o.design.empty()) designs.open(QString::fromStdString(o.design), false);
  if (!o.study_protocol.empty())
    study.start(QString::fromStdString(o.study_protocol), QString::fromStdString(o.study_participant));
  if (!o.screenshot.empty()) return screenshot(*window, link, library, jobs, study, o);
  if (o.fullscreen) window->showFullScreen();
  else window->show();
  QTimer status;
  if (!o.status_file.empty()) {
    QObject::connect(&status, &QTimer::timeout, [&] {
      knoblab::ui::write_status(QString::fromStdString(o.status_file), window->contentItem());
    });
    status.start(1000);
  }
  return QGuiApplication::exec();
}
