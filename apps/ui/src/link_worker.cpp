#include "link_worker.hpp"

#include <QDateTime>
#include <QJsonDocument>

#include <chrono>
#include <exception>

#include "knoblab/control/client.hpp"

namespace knoblab::ui {

namespace {

QVariantMap to_map(const nlohmann::json& j) {
  if (!j.is_object()) return {};
  return QJsonDocument::fromJson(QByteArray::fromStdString(j.dump())).toVariant().toMap();
}

nlohmann::json to_json(const QVariantMap& m) {
  return nlohmann::json::parse(QJsonDocument::fromVariant(m).toJson(QJsonDocument::Compact).toStdString());
}

qint64 now_ms() { return QDateTime::currentMSecsSinceEpoch(); }

}  // namespace

LinkWorker::LinkWorker(Options options) : options_(std::move(options)) { clock_.start(); }
LinkWorker::~LinkWorker() = default;

void LinkWorker::start() {
  timer_ = new QTimer(this);
  timer_->setInterval(options_.poll_ms);
  connect(timer_, &QTimer::timeout, this, &LinkWorker::tick);
  timer_->start();
  tick();
}

void LinkWorker::stop() {
  if (timer_) timer_->stop();
  // Leaving supervision without a safe-state trip: hello without a watchdog.
  if (client_) {
    try {
      client_->hello(control::HelloOptions{{control::kProtocolVersion}, "knoblab-ui", std::nullopt});
    } catch (const std::exception&) {
    }
    client_.reset();
  }
}

bool LinkWorker::connect_now() {
  try {
    auto c = std::make_unique<control::Client>(options_.socket.toStdString(), std::chrono::milliseconds(2000));
    bool supervising = false;
    if (options_.supervise) {
      try {
        c->hello({{control::kProtocolVersion}, "knoblab-ui", options_.watchdog_ms});
        supervising = true;
      } catch (const control::RemoteError& e) {
        if (e.code() != control::ErrorCode::busy) throw;
        c->hello({{control::kProtocolVersion}, "knoblab-ui", std::nullopt});
      }
    } else {
      c->hello({{control::kProtocolVersion}, "knoblab-ui", std::nullopt});
    }
    const nlohmann::json sub = c->call(
        "subscribe", {{"events", {"stats", "fault_latched", "capture_finished", "calibration_finished", "watchdog_expired",
                                   "capture_button"}},
                      {"telemetry", true}});
    const std::string shm = sub.value("telemetry_shm", "");
    client_ = std::move(c);
    last_failure_.clear();
    emit supervisingChanged(supervising);
    emit telemetryNamed(QString::fromStdString(shm));
    emit connectedChanged(true, {});
    return true;
  } catch (const std::exception& e) {
    const QString why = QString::fromUtf8(e.what());
    if (why != last_failure_) {
      last_failure_ = why;
      emit connectedChanged(false, why);
    }
    return false;
  }
}

void LinkWorker::drop(const QString& why) {
  client_.reset();
  last_failure_ = why;
  next_attempt_ms_ = now_ms() + options_.reconnect_ms;
  emit supervisingChanged(false);
  emit connectedChanged(false, why);
}

void LinkWorker::drain_events() {
  while (auto e = client_->wait_event(std::chrono::milliseconds(0)))
    emit eventArrived(QString::fromStdString(e->name), to_map(e->data));
}

void LinkWorker::tick() {
  if (!client_) {
    if (now_ms() < next_attempt_ms_) return;
    if (!connect_now()) {
      next_attempt_ms_ = now_ms() + options_.reconnect_ms;
      return;
    }
  }
  try {
    const nlohmann::json state = client_->call("get_state");
    const double at = static_cast<double>(clock_.nsecsElapsed()) * 1e-9;
    drain_events();
    emit stateArrived(to_map(state), at);
  } catch (const control::RemoteError& e) {
    emit connectedChanged(true, QString::fromUtf8(e.what()));
  } catch (const std::exception& e) {
    drop(QString::fromUtf8(e.what()));
  }
}

void LinkWorker::send(int token, const QString& cmd, const QVariantMap& args) {
  if (!client_) {
    emit replied(token, cmd, false, {}, QStringLiteral("not connected to hapticd"));
    return;
  }
  try {
    const control::Reply r = client_->request(cmd.toStdString(), to_json(args));
    if (r.ok) emit replied(token, cmd, true, to_map(r.result), {});
    else emit replied(token, cmd, false, {}, QString::fromStdString(r.error.message));
    drain_events();
  } catch (const std::exception& e) {
    emit replied(token, cmd, false, {}, QString::fromUtf8(e.what()));
    drop(QString::fromUtf8(e.what()));
  }
}

}  // namespace knoblab::ui
