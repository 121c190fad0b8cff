// Fits, discrepancy runs and comparisons, done as the CLI does them because
// they are the CLI: `knoblab fit|discrepancy --capture ID --db DB --json FILE`
// in a child process, which stores the result beside the capture (`knoblab
// compare A B` stores nothing: its result and figures come back with it). The UI stays a reader
// of the store, a crashing analysis cannot take the screen down, and the
// results are the CLI's by construction. Progress comes as JSON lines
// (KNOBLAB_PROGRESS=json); cancel() asks the command to stop (SIGTERM: it
// stores nothing). One job at a time.
#pragma once

#include <QObject>
#include <QProcess>
#include <QString>
#include <QStringList>
#include <QTemporaryDir>
#include <QVariantMap>
#include <QtQml/qqmlregistration.h>

#include <memory>

namespace knoblab::ui {

class JobRunner : public QObject {
  Q_OBJECT
  QML_ELEMENT
  QML_UNCREATABLE("knoblab-ui makes the one job runner")
  Q_PROPERTY(bool running READ running NOTIFY runningChanged)
  Q_PROPERTY(QString kind READ kind NOTIFY runningChanged)  // "fit", "discrepancy" or "compare"
  Q_PROPERTY(qint64 captureId READ captureId NOTIFY runningChanged)
  Q_PROPERTY(QString stage READ stage NOTIFY progressChanged)
  Q_PROPERTY(double fraction READ fraction NOTIFY progressChanged)  // 0…1; -1 when the stage has no count

 public:
  // `knoblab`: the CLI's path; `db`: the store.
  JobRunner(QString knoblab, QString db, QObject* parent = nullptr);
  ~JobRunner() override;

  bool running() const { return process_ != nullptr; }
  QString kind() const { return kind_; }
  qint64 captureId() const { return capture_id_; }
  QString stage() const { return stage_; }
  double fraction() const { return fraction_; }

  // Start a job; false (with a message) when one is already running.
  Q_INVOKABLE bool fit(qint64 captureId);
  Q_INVOKABLE bool discrepancy(qint64 captureId);
  // Two captures side by side (each's latest stored fit, else fitted now):
  // the result is the command's JSON plus `figures`, the overlaid
  // torque_position and torque_velocity figures' CSV text.
  Q_INVOKABLE bool compare(qint64 captureA, qint64 captureB);
  Q_INVOKABLE void cancel();

 signals:
  void runningChanged();
  void progressChanged();
  // ok: `result` is the command's JSON; else `error` says why ("cancelled"
  // when asked to stop).
  void finished(const QString& kind, qint64 captureId, bool ok, const QVariantMap& result, const QString& error);
  void message(const QString& text, const QString& level);

 private:
  bool start(const QString& kind, qint64 captureId, QStringList args);
  QVariantMap read_result() const;
  void read_progress();
  void done(int exit_code, QProcess::ExitStatus status);

  QString knoblab_, db_;
  QProcess* process_ = nullptr;
  std::unique_ptr<QTemporaryDir> scratch_;
  QString kind_, stage_, errors_;
  QByteArray pending_;
  qint64 capture_id_ = 0;
  double fraction_ = -1.0;
  bool cancelled_ = false;
};

}  // namespace knoblab::ui
