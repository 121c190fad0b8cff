// The axes both kinds of plot draw (TracePlot, FigureView): round tick
// values, a dotted grid, labels beside the frame. One definition, so the
// live traces and the report figures read alike.
#pragma once

#include <QColor>
#include <QPainter>
#include <QRectF>

namespace knoblab::ui {

// A "nice" step for about `ticks` divisions of `span`: 1, 2 or 5 × 10^k.
double nice_step(double span, int ticks);

// Grid lines and value labels for `lo … hi` along the frame `area`: left
// of it for the vertical axis, under it for the horizontal one.
void draw_ticks(QPainter& p, const QRectF& area, double lo, double hi, bool vertical, const QColor& color);

}  // namespace knoblab::ui
