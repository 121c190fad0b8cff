// A live trace of one telemetry channel over the feed's last seconds, for
// the capture wizard: the knob's angle (degrees) or torque (mN·m; with the
// torque's extremes between records as a band, so a detent click is not
// lost to decimation). Axes in presentation units; the newest sample at
// the right edge.
#pragma once

#include <QColor>
#include <QPointer>
#include <QQuickPaintedItem>
#include <QtQml/qqmlregistration.h>

#include "telemetry_feed.hpp"

namespace knoblab::ui {

class TracePlot : public QQuickPaintedItem {
  Q_OBJECT
  QML_ELEMENT
  Q_PROPERTY(knoblab::ui::TelemetryFeed* feed READ feed WRITE setFeed NOTIFY feedChanged)
  // "angle" or "torque".
  Q_PROPERTY(QString channel READ channel WRITE setChannel NOTIFY styleChanged)
  Q_PROPERTY(QColor color READ color WRITE setColor NOTIFY styleChanged)
  Q_PROPERTY(QColor textColor READ textColor WRITE setTextColor NOTIFY styleChanged)
  Q_PROPERTY(int fontPixels READ fontPixels WRITE setFontPixels NOTIFY styleChanged)
  // Records the trace holds (tests: it is not empty).
  Q_PROPERTY(int drawn READ drawn NOTIFY drawnChanged)

 public:
  explicit TracePlot(QQuickItem* parent = nullptr);
  void paint(QPainter* painter) override;

  TelemetryFeed* feed() const { return feed_; }
  void setFeed(TelemetryFeed* feed);
  QString channel() const { return channel_; }
  void setChannel(const QString& c);
  QColor color() const { return color_; }
  void setColor(const QColor& c);
  QColor textColor() const { return text_color_; }
  void setTextColor(const QColor& c);
  int fontPixels() const { return font_pixels_; }
  void setFontPixels(int px);
  int drawn() const { return drawn_; }

 signals:
  void feedChanged();
  void styleChanged();
  void drawnChanged();

 private:
  QPointer<TelemetryFeed> feed_;
  QString channel_ = QStringLiteral("angle");
  QColor color_ = QColor(0x4f, 0xb3, 0xff), text_color_ = QColor(0x9a, 0xa6, 0xb2);
  int font_pixels_ = 14;
  int drawn_ = 0;
};

}  // namespace knoblab::ui
