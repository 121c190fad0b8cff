// The loop's telemetry for live traces: the shared-memory ring hapticd
// writes (protocol §9), read without blocking 30 times a second on the UI
// thread and kept for the last `seconds`. Follows the ring by name: when
// hapticd restarts (its ring closed) it opens the new one.
#pragma once

#include <QObject>
#include <QString>
#include <QTimer>
#include <QtQml/qqmlregistration.h>

#include <deque>
#include <memory>
#include <vector>

#include "knoblab/control/telemetry_sample.hpp"

namespace knoblab::control {
class TelemetryReader;
}

namespace knoblab::ui {

class TelemetryFeed : public QObject {
  Q_OBJECT
  QML_ELEMENT
  QML_UNCREATABLE("knoblab-ui makes the one telemetry feed")
  // The ring's name; "" stops reading.
  Q_PROPERTY(QString ring READ ring WRITE setRing NOTIFY ringChanged)
  Q_PROPERTY(bool live READ live NOTIFY liveChanged)
  Q_PROPERTY(double seconds READ seconds WRITE setSeconds NOTIFY ringChanged)

 public:
  explicit TelemetryFeed(QObject* parent = nullptr);
  ~TelemetryFeed() override;

  QString ring() const { return ring_; }
  void setRing(const QString& name);
  bool live() const { return reader_ != nullptr; }
  double seconds() const { return seconds_; }
  void setSeconds(double s);

  // The kept records, oldest first (for the trace plots).
  const std::deque<control::TelemetryRecord>& records() const { return records_; }
  // Forget what was kept (a new capture starts its traces afresh).
  Q_INVOKABLE void clear();

 signals:
  void ringChanged();
  void liveChanged();
  void updated();

 private:
  void poll();
  void open();

  QString ring_;
  double seconds_ = 10.0;
  std::unique_ptr<control::TelemetryReader> reader_;
  std::vector<control::TelemetryRecord> buffer_;
  std::deque<control::TelemetryRecord> records_;
  QTimer timer_;
};

}  // namespace knoblab::ui
