#include "plot_axes.hpp"

#include <QFontMetricsF>

#include <algorithm>
#include <cmath>

namespace knoblab::ui {

double nice_step(double span, int ticks) {
  if (!(span > 0)) return 1.0;
  const double raw = span / std::max(1, ticks);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) return m * mag;
  return 10.0 * mag;
}

void draw_ticks(QPainter& p, const QRectF& area, double lo, double hi, bool vertical, const QColor& color) {
  if (!(hi > lo)) return;
  const QFontMetricsF fm(p.font());
  const double length = vertical ? area.height() : area.width();
  const int ticks = std::max(2, static_cast<int>(length / (vertical ? 3.0 * fm.height() : 6.0 * fm.height())));
  const double step = nice_step(hi - lo, ticks);
  p.setPen(QPen(color, 1, Qt::DotLine));
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
    const double shown = std::abs(v) < step * 1e-6 ? 0.0 : v;
    const QString text = QString::number(shown, 'g', 5).replace(QLatin1Char('-'), QChar(0x2212));
    if (vertical) {
      const double y = area.bottom() - (v - lo) / (hi - lo) * area.height();
      p.drawLine(QPointF(area.left(), y), QPointF(area.right(), y));
      p.drawText(QRectF(0, y - fm.height() / 2, area.left() - 4, fm.height()), Qt::AlignRight | Qt::AlignVCenter, text);
    } else {
      const double x = area.left() + (v - lo) / (hi - lo) * area.width();
      p.drawLine(QPointF(x, area.top()), QPointF(x, area.bottom()));
      const double w = fm.horizontalAdvance(text);
      p.drawText(QRectF(x - w / 2, area.bottom() + 2, w, fm.height()), Qt::AlignCenter, text);
    }
  }
}

}  // namespace knoblab::ui
