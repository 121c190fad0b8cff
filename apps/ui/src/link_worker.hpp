// The UI's connection to hapticd, on a thread of its own: the control
// protocol's client blocks for up to its timeout, which the UI thread must
// never do. It polls get_state, passes events on, sends the UI's requests,
// and reconnects by itself when the daemon goes away or restarts.
#pragma once

#include <QElapsedTimer>
#include <QObject>
#include <QString>
#include <QTimer>
#include <QVariantMap>

#include <memory>

namespace knoblab::control {
class Client;
}

namespace knoblab::ui {

class LinkWorker : public QObject {
  Q_OBJECT
 public:
  struct Options {
    QString socket;
    // Supervise the daemon (protocol §6): if this UI stops answering, the
    // motor goes safe. Another supervisor already there: connect unsupervised.
    bool supervise = true;
    int watchdog_ms = 1000;
    int poll_ms = 200;       // get_state (and the watchdog's ping)
    int reconnect_ms = 1000;
  };
  explicit LinkWorker(Options options);
  ~LinkWorker() override;

 public slots:
  void start();  // on the worker thread
  void stop();
  // One request; its reply comes back as replied(token, …).
  void send(int token, const QString& cmd, const QVariantMap& args);

 signals:
  void connectedChanged(bool connected, const QString& why);
  void supervisingChanged(bool supervising);
  // The telemetry ring's shared-memory name ("" when hapticd keeps none).
  void telemetryNamed(const QString& name);
  // `seconds`: when the reply came, on this worker's steady clock (the UI
  // thread may handle two replies in one go; the loop rate needs their timing).
  void stateArrived(const QVariantMap& state, double seconds);
  void eventArrived(const QString& name, const QVariantMap& data);
  void replied(int token, const QString& cmd, bool ok, const QVariantMap& result, const QString& error);

 private:
  void tick();
  bool connect_now();
  void drop(const QString& why);
  void drain_events();

  Options options_;
  QTimer* timer_ = nullptr;
  std::unique_ptr<control::Client> client_;
  QString last_failure_;  // said once, not at every retry
  qint64 next_attempt_ms_ = 0;
  QElapsedTimer clock_;
};

}  // namespace knoblab::ui
