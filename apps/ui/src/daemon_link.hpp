// hapticd as QML sees it: connection, mode, loop rate, faults, the state
// and the loop statistics, and the requests the screens make. The
// connection itself runs on a LinkWorker thread; this object lives on the
// UI thread and only ever receives its signals (queued), so nothing here
// blocks.
#pragma once

#include <QObject>
#include <QStringList>
#include <QThread>
#include <QVariantMap>
#include <QtQml/qqmlregistration.h>

#include "daemon_state.hpp"
#include "link_worker.hpp"

namespace knoblab::ui {

class DaemonLink : public QObject {
  Q_OBJECT
  QML_ELEMENT
  QML_UNCREATABLE("knoblab-ui makes the one link to hapticd")
  Q_PROPERTY(QString socket READ socket CONSTANT)
  Q_PROPERTY(bool connected READ connected NOTIFY connectedChanged)
  Q_PROPERTY(bool supervising READ supervising NOTIFY supervisingChanged)
  // Why the link is down ("" while up).
  Q_PROPERTY(QString problem READ problem NOTIFY connectedChanged)
  Q_PROPERTY(QVariantMap state READ state NOTIFY stateChanged)
  // A state read from hapticd on the connection that is up now: without one
  // the strip says "unknown", never "ok", for what it has not read.
  Q_PROPERTY(bool stateKnown READ stateKnown NOTIFY stateChanged)
  Q_PROPERTY(QVariantMap stats READ stats NOTIFY statsChanged)
  Q_PROPERTY(QString mode READ mode NOTIFY stateChanged)
  Q_PROPERTY(QStringList faults READ faults NOTIFY stateChanged)
  Q_PROPERTY(bool estop READ estop NOTIFY stateChanged)
  Q_PROPERTY(bool amplifierFault READ amplifierFault NOTIFY stateChanged)
  // The Modbus poller in words ("ok", "off", "biometrics stale"), and whether all is well.
  Q_PROPERTY(QString modbus READ modbus NOTIFY stateChanged)
  Q_PROPERTY(bool modbusOk READ modbusOk NOTIFY stateChanged)
  // The telemetry ring hapticd writes ("" when none, or not connected).
  Q_PROPERTY(QString telemetryName READ telemetryName NOTIFY telemetryNameChanged)
  // The loop's rate as measured from its cycle counter (0 until known).
  Q_PROPERTY(double measuredRateHz READ measuredRateHz NOTIFY stateChanged)

 public:
  explicit DaemonLink(LinkWorker::Options options, QObject* parent = nullptr);
  ~DaemonLink() override;

  QString socket() const { return socket_; }
  bool connected() const { return connected_; }
  bool supervising() const { return supervising_; }
  QString problem() const { return problem_; }
  QVariantMap state() const { return state_; }
  bool stateKnown() const { return state_known_; }
  QVariantMap stats() const { return stats_; }
  QString mode() const { return state_.value(QStringLiteral("mode")).toString(); }
  QStringList faults() const { return state_.value(QStringLiteral("faults")).toStringList(); }
  bool estop() const { return faults_.estop; }
  bool amplifierFault() const { return faults_.amplifier; }
  QString modbus() const { return QString::fromStdString(modbus_.text); }
  bool modbusOk() const { return modbus_.ok; }
  double measuredRateHz() const { return rate_hz_; }
  QString telemetryName() const { return telemetry_name_; }

  // A request to hapticd; its outcome comes back as replied(token, …) and,
  // when it failed, as a message. Returns the token.
  Q_INVOKABLE int request(const QString& cmd, const QVariantMap& args = {});
  Q_INVOKABLE int clearFault() { return request(QStringLiteral("clear_fault")); }

 signals:
  void connectedChanged();
  void supervisingChanged();
  void telemetryNameChanged();
  void stateChanged();
  void statsChanged();
  void event(const QString& name, const QVariantMap& data);
  void replied(int token, const QString& cmd, bool ok, const QVariantMap& result, const QString& error);
  // For the message bar: level "info", "warning" or "error".
  void message(const QString& text, const QString& level);
  // To the worker (queued across threads).
  void sendRequested(int token, const QString& cmd, const QVariantMap& args);

 private:
  void on_connected(bool up, const QString& why);
  void on_state(const QVariantMap& state, double seconds);
  void on_event(const QString& name, const QVariantMap& data);

  QString socket_;
  QThread thread_;
  LinkWorker* worker_ = nullptr;
  bool connected_ = false, supervising_ = false;
  bool ever_connected_ = false;  // a later connection is news ("reconnected")
  bool state_known_ = false;     // on_state since the connection came up
  QString problem_, telemetry_name_;
  QVariantMap state_, stats_;
  FaultReading faults_;
  ModbusReading modbus_{true, "–"};
  LoopRateMeter meter_;
  double rate_hz_ = 0.0;
  int next_token_ = 1;
};

}  // namespace knoblab::ui
