#include "daemon_link.hpp"

#include <QMetaObject>

namespace knoblab::ui {

DaemonLink::DaemonLink(LinkWorker::Options options, QObject* parent)
    : QObject(parent), socket_(options.socket) {
  worker_ = new LinkWorker(std::move(options));
  worker_->moveToThread(&thread_);
  connect(&thread_, &QThread::finished, worker_, &QObject::deleteLater);
  connect(&thread_, &QThread::started, worker_, &LinkWorker::start);
  connect(worker_, &LinkWorker::connectedChanged, this, &DaemonLink::on_connected);
  connect(worker_, &LinkWorker::supervisingChanged, this, [this](bool s) {
    if (s == supervising_) return;
    supervising_ = s;
    emit supervisingChanged();
  });
  connect(worker_, &LinkWorker::telemetryNamed, this, [this](const QString& name) {
    if (name == telemetry_name_) return;
    telemetry_name_ = name;
    emit telemetryNameChanged();
  });
  connect(worker_, &LinkWorker::stateArrived, this, &DaemonLink::on_state);
  connect(worker_, &LinkWorker::eventArrived, this, &DaemonLink::on_event);
  connect(worker_, &LinkWorker::replied, this,
          [this](int token, const QString& cmd, bool ok, const QVariantMap& result, const QString& error) {
            if (!ok) emit message(cmd + QStringLiteral(": ") + error, QStringLiteral("error"));
            emit replied(token, cmd, ok, result, error);
          });
  connect(this, &DaemonLink::sendRequested, worker_, &LinkWorker::send);
  thread_.setObjectName(QStringLiteral("hapticd link"));
  thread_.start();
}

DaemonLink::~DaemonLink() {
  QMetaObject::invokeMethod(worker_, &LinkWorker::stop, Qt::BlockingQueuedConnection);
  thread_.quit();
  thread_.wait();
}

int DaemonLink::request(const QString& cmd, const QVariantMap& args) {
  const int token = next_token_++;
  emit sendRequested(token, cmd, args);
  return token;
}

void DaemonLink::on_connected(bool up, const QString& why) {
  if (up && !why.isEmpty()) {  // up, but a request was refused
    emit message(why, QStringLiteral("warning"));
    return;
  }
  const bool changed = up != connected_ || why != problem_;
  // The strip shows the link; the bar says when it changes, not that the
  // first connection came up.
  if (up && !connected_ && ever_connected_) emit message(QStringLiteral("reconnected to hapticd"), QStringLiteral("info"));
  if (!up && connected_) emit message(QStringLiteral("lost hapticd: ") + why + QStringLiteral(" (reconnecting)"), QStringLiteral("error"));
  ever_connected_ = ever_connected_ || up;
  connected_ = up;
  problem_ = up ? QString() : why;
  const bool forget = !up && state_known_;
  if (!up) {
    meter_.reset();
    rate_hz_ = 0.0;
    state_known_ = false;
  }
  if (changed) emit connectedChanged();
  if (forget) emit stateChanged();
}

void DaemonLink::on_state(const QVariantMap& state, double seconds) {
  state_ = state;
  state_known_ = connected_;
  std::vector<std::string> names;
  for (const QString& f : state.value(QStringLiteral("faults")).toStringList()) names.push_back(f.toStdString());
  faults_ = read_faults(names);
  modbus_ = read_modbus(state.value(QStringLiteral("modbus")).toString().toStdString());
  const auto cycles = state.value(QStringLiteral("cycles")).toULongLong();
  rate_hz_ = meter_.update(cycles, seconds).value_or(0.0);
  emit stateChanged();
}

void DaemonLink::on_event(const QString& name, const QVariantMap& data) {
  if (name == QStringLiteral("stats")) {
    stats_ = data;
    emit statsChanged();
  } else if (name == QStringLiteral("fault_latched")) {
    emit message(QStringLiteral("fault: ") + data.value(QStringLiteral("faults")).toStringList().join(QStringLiteral(", ")),
                 QStringLiteral("error"));
  } else if (name == QStringLiteral("watchdog_expired")) {
    emit message(QStringLiteral("hapticd's watchdog expired: the motor was made safe"), QStringLiteral("warning"));
  }
  emit event(name, data);
}

}  // namespace knoblab::ui
