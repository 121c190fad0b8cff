// A report figure drawn for touch: one panel of a figure's CSV
// (figure_data.hpp), its points, lines and bands, with pinch to zoom, drag to
// pan (zoomAt, panBy: the QML handlers call them) and tap for the values at
// a point (valueAt: the nearest plotted point).
#pragma once

#include <QColor>
#include <QQuickPaintedItem>
#include <QStringList>
#include <QtQml/qqmlregistration.h>

#include "figure_data.hpp"

namespace knoblab::ui {

class FigureView : public QQuickPaintedItem {
  Q_OBJECT
  QML_ELEMENT
  // The figure's CSV text; "" shows nothing. A malformed one sets `error`.
  Q_PROPERTY(QString csv READ csv WRITE setCsv NOTIFY figureChanged)
  Q_PROPERTY(QString panel READ panel WRITE setPanel NOTIFY viewChanged)
  Q_PROPERTY(QStringList panels READ panels NOTIFY figureChanged)
  Q_PROPERTY(QString error READ error NOTIFY figureChanged)
  Q_PROPERTY(QColor textColor READ textColor WRITE setTextColor NOTIFY viewChanged)
  Q_PROPERTY(int fontPixels READ fontPixels WRITE setFontPixels NOTIFY viewChanged)
  // The colours of a comparison's sides (series a_… and b_…), for legends.
  Q_PROPERTY(QColor colourA READ colourA CONSTANT)
  Q_PROPERTY(QColor colourB READ colourB CONSTANT)
  // Points of the panel drawn (tests: the plot is not empty).
  Q_PROPERTY(int points READ points NOTIFY viewChanged)

 public:
  explicit FigureView(QQuickItem* parent = nullptr);
  void paint(QPainter* painter) override;

  QString csv() const { return csv_; }
  void setCsv(const QString& text);
  QString panel() const { return panel_; }
  void setPanel(const QString& p);
  QStringList panels() const;
  QString error() const { return error_; }
  QColor textColor() const { return text_color_; }
  void setTextColor(const QColor& c);
  int fontPixels() const { return font_pixels_; }
  void setFontPixels(int px);
  int points() const;
  static QColor colourA();
  static QColor colourB();

  // Zoom by `factor` (> 1: in) about the item point (px, py); pan by pixels.
  Q_INVOKABLE void zoomAt(qreal factor, qreal px, qreal py);
  Q_INVOKABLE void panBy(qreal dx, qreal dy);
  Q_INVOKABLE void resetView();
  // The plotted point nearest the item point, as text ("" when none).
  Q_INVOKABLE QString valueAt(qreal px, qreal py) const;

 signals:
  void figureChanged();
  void viewChanged();

 private:
  QRectF plot_area() const;
  void fit_view();

  QString csv_, panel_, error_;
  FigureData figure_;
  QColor text_color_ = QColor(0x9a, 0xa6, 0xb2);
  int font_pixels_ = 14;
  double x0_ = 0, x1_ = 1, y0_ = 0, y1_ = 1;  // the view, in the CSV's units
};

}  // namespace knoblab::ui
