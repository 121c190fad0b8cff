#include "job_runner.hpp"

#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcessEnvironment>

namespace knoblab::ui {

JobRunner::JobRunner(QString knoblab, QString db, QObject* parent)
    : QObject(parent), knoblab_(std::move(knoblab)), db_(std::move(db)) {}

JobRunner::~JobRunner() {
  if (process_) {
    process_->disconnect(this);
    process_->terminate();
    if (!process_->waitForFinished(3000)) process_->kill();
    process_->waitForFinished(1000);
  }
}

namespace {

// Each comparison's overlaid figures, as `knoblab compare --report` names them.
const QStringList kCompareFigures = {QStringLiteral("torque_position"), QStringLiteral("torque_velocity")};

}  // namespace

bool JobRunner::fit(qint64 captureId) {
  return start(QStringLiteral("fit"), captureId, {QStringLiteral("--capture"), QString::number(captureId)});
}
bool JobRunner::discrepancy(qint64 captureId) {
  return start(QStringLiteral("discrepancy"), captureId, {QStringLiteral("--capture"), QString::number(captureId)});
}
bool JobRunner::compare(qint64 captureA, qint64 captureB) {
  return start(QStringLiteral("compare"), captureA, {QString::number(captureA), QString::number(captureB)});
}

bool JobRunner::start(const QString& kind, qint64 captureId, QStringList args) {
  if (process_) {
    emit message(QStringLiteral("a %1 of capture %2 is still running").arg(kind_).arg(capture_id_),
                 QStringLiteral("warning"));
    return false;
  }
  scratch_ = std::make_unique<QTemporaryDir>();
  kind_ = kind;
  capture_id_ = captureId;
  stage_ = QStringLiteral("starting");
  fraction_ = -1.0;
  errors_.clear();
  pending_.clear();
  cancelled_ = false;
  process_ = new QProcess(this);
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert(QStringLiteral("KNOBLAB_PROGRESS"), QStringLiteral("json"));
  process_->setProcessEnvironment(env);
  connect(process_, &QProcess::readyReadStandardError, this, &JobRunner::read_progress);
  connect(process_, &QProcess::finished, this, &JobRunner::done);
  connect(process_, &QProcess::errorOccurred, this, [this](QProcess::ProcessError e) {
    if (e == QProcess::FailedToStart) {
      errors_ = QStringLiteral("cannot run %1: %2").arg(knoblab_, process_->errorString());
      done(-1, QProcess::CrashExit);
    }
  });
  // The report too, stored with the result: its figures' CSVs are what the
  // review screens plot (small PNGs: the pictures are not what is wanted).
  args.prepend(kind);
  args << QStringLiteral("--db") << db_ << QStringLiteral("--json") << scratch_->filePath(QStringLiteral("result.json"))
       << QStringLiteral("--report") << scratch_->filePath(QStringLiteral("report")) << QStringLiteral("--format")
       << QStringLiteral("png") << QStringLiteral("--dpi") << QStringLiteral("50");
  process_->start(knoblab_, args);
  emit runningChanged();
  emit progressChanged();
  return true;
}

void JobRunner::cancel() {
  if (!process_) return;
  cancelled_ = true;
  process_->terminate();  // SIGTERM: the command stops cleanly, storing nothing
}

void JobRunner::read_progress() {
  pending_ += process_->readAllStandardError();
  for (qsizetype nl; (nl = pending_.indexOf('\n')) >= 0;) {
    const QByteArray line = pending_.left(nl);
    pending_.remove(0, nl + 1);
    const QJsonObject p = QJsonDocument::fromJson(line).object().value(QStringLiteral("progress")).toObject();
    if (p.isEmpty()) {
      if (!line.trimmed().isEmpty()) errors_ = QString::fromUtf8(line.trimmed());  // the last says why
      continue;
    }
    stage_ = p.value(QStringLiteral("stage")).toString();
    const double total = p.value(QStringLiteral("total")).toDouble();
    fraction_ = total > 0 ? p.value(QStringLiteral("done")).toDouble() / total : -1.0;
    emit progressChanged();
  }
}

QVariantMap JobRunner::read_result() const {
  QFile f(scratch_->filePath(QStringLiteral("result.json")));
  if (!f.open(QIODevice::ReadOnly)) return {};
  QVariantMap result = QJsonDocument::fromJson(f.readAll()).toVariant().toMap();
  if (kind_ == QStringLiteral("compare") && !result.isEmpty()) {
    // The scratch directory goes with the job: the figures travel as text.
    QVariantMap figures;
    for (const QString& name : kCompareFigures) {
      QFile csv(scratch_->filePath(QStringLiteral("report/%1.csv").arg(name)));
      if (csv.open(QIODevice::ReadOnly)) figures.insert(name, QString::fromUtf8(csv.readAll()));
    }
    result.insert(QStringLiteral("figures"), figures);
  }
  return result;
}

void JobRunner::done(int exit_code, QProcess::ExitStatus status) {
  if (!process_) return;
  read_progress();
  const QString kind = kind_;
  const qint64 id = capture_id_;
  QVariantMap result;
  QString error;
  if (cancelled_) {
    error = QStringLiteral("cancelled");
  } else if (status != QProcess::NormalExit || exit_code != 0) {
    error = errors_.isEmpty() ? QStringLiteral("knoblab %1 exited with status %2").arg(kind).arg(exit_code) : errors_;
  } else {
    result = read_result();
    if (result.isEmpty()) error = QStringLiteral("knoblab %1 wrote no result").arg(kind);
  }
  process_->deleteLater();
  process_ = nullptr;
  scratch_.reset();
  stage_.clear();
  fraction_ = -1.0;
  emit runningChanged();
  emit progressChanged();
  if (!error.isEmpty() && error != QStringLiteral("cancelled"))
    emit message(QStringLiteral("%1 of capture %2 failed: %3").arg(kind).arg(id).arg(error), QStringLiteral("error"));
  emit finished(kind, id, error.isEmpty(), result, error);
}

}  // namespace knoblab::ui
