#include "trace_plot.hpp"

#include "plot_axes.hpp"

#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace knoblab::ui {

TracePlot::TracePlot(QQuickItem* parent) : QQuickPaintedItem(parent) { setAntialiasing(true); }

void TracePlot::setFeed(TelemetryFeed* feed) {
  if (feed == feed_) return;
  if (feed_) disconnect(feed_, nullptr, this, nullptr);
  feed_ = feed;
  if (feed_)
    connect(feed_, &TelemetryFeed::updated, this, [this] {
      const int n = static_cast<int>(feed_->records().size());
      if (n != drawn_) {
        drawn_ = n;
        emit drawnChanged();
      }
      update();
    });
  emit feedChanged();
  update();
}

void TracePlot::setChannel(const QString& c) {
  if (c == channel_) return;
  channel_ = c;
  emit styleChanged();
  update();
}
void TracePlot::setColor(const QColor& c) {
  color_ = c;
  emit styleChanged();
  update();
}
void TracePlot::setTextColor(const QColor& c) {
  text_color_ = c;
  emit styleChanged();
  update();
}
void TracePlot::setFontPixels(int px) {
  font_pixels_ = px;
  emit styleChanged();
  update();
}

void TracePlot::paint(QPainter* p) {
  const bool torque = channel_ == QStringLiteral("torque");
  // Presentation units at the edge: degrees, mN·m.
  const double scale = torque ? 1e3 : 180.0 / std::numbers::pi;
  const QString unit = torque ? QStringLiteral("mN·m") : QStringLiteral("°");
  QFont font = p->font();
  font.setPixelSize(font_pixels_);
  p->setFont(font);
  const QFontMetricsF fm(font);
  const double left = fm.horizontalAdvance(QStringLiteral("−0000.0")) + 6, bottom = fm.height() + 4;
  const QRectF area(left, 4, width() - left - 4, height() - bottom - 8);
  p->setPen(QPen(text_color_, 1));
  p->drawRect(area);
  if (feed_ && !feed_->records().empty() && area.width() > 10 && area.height() > 10) {
    const auto& rec = feed_->records();
    const double t1 = rec.back().t, t0 = t1 - feed_->seconds();
    double lo = 1e300, hi = -1e300;
    for (const auto& r : rec) {
      lo = std::min(lo, (torque ? r.torque_min : r.theta) * scale);
      hi = std::max(hi, (torque ? r.torque_max : r.theta) * scale);
    }
    if (hi - lo < 1e-9) lo -= 1, hi += 1;
    const double pad = 0.08 * (hi - lo);
    lo -= pad, hi += pad;
    const auto X = [&](double t) { return area.left() + (t - t0) / (t1 - t0) * area.width(); };
    const auto Y = [&](double v) { return area.bottom() - (v - lo) / (hi - lo) * area.height(); };
    draw_ticks(*p, area, lo, hi, true, text_color_);
    p->drawText(QRectF(area.left(), area.bottom() + 2, area.width(), bottom),
                Qt::AlignLeft | Qt::AlignTop, QStringLiteral("−%1 s").arg(feed_->seconds(), 0, 'g', 3));
    p->drawText(QRectF(area.left(), area.bottom() + 2, area.width(), bottom), Qt::AlignRight | Qt::AlignTop,
                (torque ? QStringLiteral("torque, ") : QStringLiteral("angle, ")) + unit);
    p->setClipRect(area);
    if (torque) {  // the extremes within each record's window, as a band
      QPainterPath band;
      bool first = true;
      for (const auto& r : rec) {
        const QPointF q(X(r.t), Y(r.torque_max * scale));
        first ? band.moveTo(q) : band.lineTo(q);
        first = false;
      }
      for (auto it = rec.rbegin(); it != rec.rend(); ++it) band.lineTo(X(it->t), Y(it->torque_min * scale));
      band.closeSubpath();
      QColor fill = color_;
      fill.setAlphaF(0.3f);
      p->fillPath(band, fill);
    }
    QPainterPath line;
    bool first = true;
    for (const auto& r : rec) {
      const QPointF q(X(r.t), Y((torque ? r.torque : r.theta) * scale));
      first ? line.moveTo(q) : line.lineTo(q);
      first = false;
    }
    p->setPen(QPen(color_, 2));
    p->drawPath(line);
  } else {
    p->drawText(area, Qt::AlignCenter, feed_ && feed_->live() ? QStringLiteral("waiting for the loop")
                                                              : QStringLiteral("no telemetry from hapticd"));
  }
}

}  // namespace knoblab::ui
