#include "figure_view.hpp"

#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "plot_axes.hpp"

namespace knoblab::ui {

namespace {

// Lines in the report's colours (matplotlib's tab10 blue, orange, red, …).
const QColor kLines[] = {QColor(0x1f, 0x77, 0xb4), QColor(0xff, 0x7f, 0x0e), QColor(0xd6, 0x27, 0x28),
                         QColor(0x2c, 0xa0, 0x2c), QColor(0x94, 0x67, 0xbd)};
const QColor kPoints(0x8a, 0x93, 0x9d);

// A comparison's two sides keep one colour each, whatever their order: A's
// series ("a_data", "a_model") blue, B's orange; the data lighter, under
// the model. Other series take the next colour in turn.
QColor series_colour(const std::string& name, bool points, int& next) {
  const bool a = name.rfind("a_", 0) == 0, b = name.rfind("b_", 0) == 0;
  QColor c = a ? kLines[0] : b ? kLines[1] : kLines[next++ % std::size(kLines)];
  if ((a || b) && points && name.find("data") != std::string::npos) c.setAlpha(70);
  return c;
}

std::string shown(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

QColor FigureView::colourA() { return kLines[0]; }
QColor FigureView::colourB() { return kLines[1]; }

FigureView::FigureView(QQuickItem* parent) : QQuickPaintedItem(parent) { setAntialiasing(true); }

void FigureView::setCsv(const QString& text) {
  if (text == csv_) return;
  csv_ = text;
  error_.clear();
  figure_ = {};
  if (!text.isEmpty()) {
    try {
      figure_ = parse_figure_csv(text.toStdString());
    } catch (const std::invalid_argument& e) {
      error_ = QString::fromUtf8(e.what());
    }
  }
  if (!figure_.panels.empty() &&
      std::find(figure_.panels.begin(), figure_.panels.end(), panel_.toStdString()) == figure_.panels.end())
    panel_ = QString::fromStdString(figure_.panels.front());
  fit_view();
  emit figureChanged();
  emit viewChanged();
  update();
}

void FigureView::setPanel(const QString& p) {
  if (p == panel_) return;
  panel_ = p;
  fit_view();
  emit viewChanged();
  update();
}

QStringList FigureView::panels() const {
  QStringList out;
  for (const std::string& p : figure_.panels) out << QString::fromStdString(p);
  return out;
}

void FigureView::setTextColor(const QColor& c) {
  text_color_ = c;
  emit viewChanged();
  update();
}

void FigureView::setFontPixels(int px) {
  font_pixels_ = px;
  emit viewChanged();
  update();
}

int FigureView::points() const {
  std::size_t n = 0;
  for (const FigureSeries& s : figure_.series)
    if (QString::fromStdString(s.panel) == panel_) n += s.x.size();
  return static_cast<int>(n);
}

QRectF FigureView::plot_area() const {
  QFont font;
  font.setPixelSize(font_pixels_);
  const QFontMetricsF fm(font);
  const double left = fm.horizontalAdvance(QStringLiteral("−00000")) + 8;
  return QRectF(left, 4, width() - left - 6, height() - 2.5 * fm.height() - 10);
}

void FigureView::fit_view() {
  double xl = std::numeric_limits<double>::infinity(), xh = -xl, yl = xl, yh = -xl;
  for (const FigureSeries& s : figure_.series) {
    if (QString::fromStdString(s.panel) != panel_) continue;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i])) continue;
      xl = std::min(xl, s.x[i]), xh = std::max(xh, s.x[i]);
      for (const double v : {s.y[i], s.y_low.empty() ? s.y[i] : s.y_low[i]})
        if (std::isfinite(v)) yl = std::min(yl, v), yh = std::max(yh, v);
    }
  }
  if (!(xh > xl)) xl -= 1, xh += 1;
  if (!(yh > yl)) yl -= 1, yh += 1;
  const double px = 0.02 * (xh - xl), py = 0.05 * (yh - yl);
  x0_ = xl - px, x1_ = xh + px, y0_ = yl - py, y1_ = yh + py;
}

void FigureView::resetView() {
  fit_view();
  emit viewChanged();
  update();
}

void FigureView::zoomAt(qreal factor, qreal px, qreal py) {
  if (!(factor > 0)) return;
  const QRectF a = plot_area();
  const double cx = x0_ + (px - a.left()) / a.width() * (x1_ - x0_);
  const double cy = y1_ - (py - a.top()) / a.height() * (y1_ - y0_);
  x0_ = cx + (x0_ - cx) / factor, x1_ = cx + (x1_ - cx) / factor;
  y0_ = cy + (y0_ - cy) / factor, y1_ = cy + (y1_ - cy) / factor;
  emit viewChanged();
  update();
}

void FigureView::panBy(qreal dx, qreal dy) {
  const QRectF a = plot_area();
  const double sx = (x1_ - x0_) / a.width() * dx, sy = (y1_ - y0_) / a.height() * dy;
  x0_ -= sx, x1_ -= sx, y0_ += sy, y1_ += sy;
  emit viewChanged();
  update();
}

QString FigureView::valueAt(qreal px, qreal py) const {
  const QRectF a = plot_area();
  double best = std::numeric_limits<double>::infinity();
  QString out;
  for (const FigureSeries& s : figure_.series) {
    if (QString::fromStdString(s.panel) != panel_) continue;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const double X = a.left() + (s.x[i] - x0_) / (x1_ - x0_) * a.width();
      const double Y = a.bottom() - (s.y[i] - y0_) / (y1_ - y0_) * a.height();
      const double dist = std::hypot(X - px, Y - py);
      if (std::isfinite(dist) && dist < best) {
        best = dist;
        out = QString::fromStdString(axis_label(figure_.x_column) + " " + shown(s.x[i]) + ", " +
                                     axis_label(figure_.y_column) + " " + shown(s.y[i]) + " — " + s.name);
      }
    }
  }
  return best < 40 ? out : QString();
}

void FigureView::paint(QPainter* p) {
  QFont font = p->font();
  font.setPixelSize(font_pixels_);
  p->setFont(font);
  const QFontMetricsF fm(font);
  const QRectF a = plot_area();
  if (a.width() < 20 || a.height() < 20) return;
  p->setPen(QPen(text_color_, 1));
  p->drawRect(a);
  if (!error_.isEmpty() || figure_.series.empty()) {
    p->drawText(a, Qt::AlignCenter | Qt::TextWordWrap, error_.isEmpty() ? QStringLiteral("no figure") : error_);
    return;
  }
  draw_ticks(*p, a, y0_, y1_, true, text_color_);
  draw_ticks(*p, a, x0_, x1_, false, text_color_);
  p->setPen(text_color_);
  p->drawText(QRectF(a.left(), a.bottom() + fm.height() + 4, a.width(), fm.height()), Qt::AlignHCenter,
              QString::fromStdString(axis_label(figure_.x_column)));
  p->drawText(QRectF(a.left() + 4, a.top() + 2, a.width() - 8, fm.height()), Qt::AlignLeft,
              QString::fromStdString(axis_label(figure_.y_column)));
  const auto X = [&](double x) { return a.left() + (x - x0_) / (x1_ - x0_) * a.width(); };
  const auto Y = [&](double y) { return a.bottom() - (y - y0_) / (y1_ - y0_) * a.height(); };
  p->save();
  p->setClipRect(a);
  int line = 0;
  // Bands first, then points, then lines over them (the report's order).
  for (const auto kind : {FigureSeries::Kind::Band, FigureSeries::Kind::Points, FigureSeries::Kind::Line}) {
    for (const FigureSeries& s : figure_.series) {
      if (QString::fromStdString(s.panel) != panel_ || s.kind != kind) continue;
      if (kind == FigureSeries::Kind::Band) {
        QPainterPath band;
        bool first = true;
        for (std::size_t i = 0; i < s.x.size(); ++i) {
          if (!std::isfinite(s.y[i])) continue;
          const QPointF q(X(s.x[i]), Y(s.y[i]));
          first ? band.moveTo(q) : band.lineTo(q);
          first = false;
        }
        for (std::size_t i = s.x.size(); i-- > 0;)
          if (std::isfinite(s.y_low[i])) band.lineTo(X(s.x[i]), Y(s.y_low[i]));
        p->fillPath(band, QColor(0x4f, 0xb3, 0xff, 60));
      } else if (kind == FigureSeries::Kind::Points) {
        // Raw data light grey under everything; a model's points (total torque
        // against θ is no function of θ) in its line colour.
        const bool raw = s.name.rfind("raw", 0) == 0;
        p->setPen(QPen(raw ? kPoints : series_colour(s.name, true, line), raw ? 2 : 2.5));
        for (std::size_t i = 0; i < s.x.size(); ++i)
          if (std::isfinite(s.y[i])) p->drawPoint(QPointF(X(s.x[i]), Y(s.y[i])));
      } else {
        QPainterPath path;
        bool first = true;
        for (std::size_t i = 0; i < s.x.size(); ++i) {
          if (!std::isfinite(s.y[i])) {
            first = true;
            continue;
          }
          const QPointF q(X(s.x[i]), Y(s.y[i]));
          first ? path.moveTo(q) : path.lineTo(q);
          first = false;
        }
        p->setPen(QPen(series_colour(s.name, false, line), 2));
        p->drawPath(path);
      }
    }
  }
  p->restore();
}

}  // namespace knoblab::ui
