// What a rendered screen must satisfy (the screenshot tests and
// knoblab-ui --screenshot): something drawn, and every visible text whole —
// not elided, not wider than its box, not cut by the window or a clipping
// parent.
#pragma once

#include <QImage>
#include <QQuickItem>
#include <QString>
#include <QStringList>

namespace knoblab::ui {

// Problems found, one line each ("" list: none).
QStringList clipped_texts(QQuickItem* root);

// The visible texts that have an objectName, as "name: text" lines in
// item order: what a test (or the image test) reads off a screen.
QStringList named_texts(QQuickItem* root);

// The named texts as a JSON object {"texts": {name: text, …}}, written to
// `path` atomically (a temporary file renamed over it). False when it could
// not be written.
bool write_status(const QString& path, QQuickItem* root);

// Whether the image shows more than a blank fill: at least 2 % of its pixels
// differ from its most common colour.
bool drawn(const QImage& image);

}  // namespace knoblab::ui
