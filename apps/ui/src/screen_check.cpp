#include "screen_check.hpp"

#include <QHash>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QRectF>

#include <algorithm>

namespace knoblab::ui {

namespace {

// Half a pixel of rounding either way is not clipping.
constexpr qreal kSlack = 1.0;

bool is_text(const QQuickItem* item) { return item->inherits("QQuickText") || item->inherits("QQuickTextEdit"); }

QString label(const QQuickItem* item) {
  QString text = item->property("text").toString().simplified();
  if (text.size() > 40) text = text.left(37) + QStringLiteral("…");
  return QStringLiteral("'") + text + QStringLiteral("'");
}

bool contains(const QRectF& outer, const QRectF& inner) {
  return inner.left() >= outer.left() - kSlack && inner.top() >= outer.top() - kSlack &&
         inner.right() <= outer.right() + kSlack && inner.bottom() <= outer.bottom() + kSlack;
}

// Inside a Flickable (a ListView, a scrolling panel) a text may lie beyond
// the viewport or across its edge: it scrolls into view. There only its own
// box is checked; the window and the clipping parents above the flickable
// still bound the flickable itself.
void check(QQuickItem* item, const QRectF& window, QList<QRectF> clips, bool scrolls, QStringList& out) {
  if (!item->isVisible() || item->opacity() <= 0.0) return;
  const QRectF box = item->mapRectToScene(QRectF(0, 0, item->width(), item->height()));
  if (is_text(item) && !item->property("text").toString().trimmed().isEmpty()) {
    const qreal cw = item->property("contentWidth").toReal(), ch = item->property("contentHeight").toReal();
    if (item->property("truncated").toBool()) out << label(item) + QStringLiteral(" is elided or truncated");
    else if (cw > item->width() + kSlack)
      out << label(item) + QStringLiteral(" needs %1 px of width, has %2").arg(cw, 0, 'f', 0).arg(item->width(), 0, 'f', 0);
    else if (ch > item->height() + kSlack)
      out << label(item) + QStringLiteral(" needs %1 px of height, has %2").arg(ch, 0, 'f', 0).arg(item->height(), 0, 'f', 0);
    // Where its glyphs are drawn: the content box, aligned within the item.
    const QRectF drawn_box = item->mapRectToScene(QRectF(0, 0, std::min(cw, item->width()), std::min(ch, item->height())));
    if (scrolls) {
      // checked above: not elided, fits its box
    } else if (!contains(window, drawn_box)) out << label(item) + QStringLiteral(" runs off the window");
    else
      for (const QRectF& c : clips)
        if (!contains(c, drawn_box)) {
          out << label(item) + QStringLiteral(" is cut by a clipping parent");
          break;
        }
  }
  if (item->clip()) clips.append(box);
  const bool inside = scrolls || item->inherits("QQuickFlickable");
  for (QQuickItem* child : item->childItems()) check(child, window, clips, inside, out);
}

}  // namespace

QStringList clipped_texts(QQuickItem* root) {
  QStringList out;
  if (!root) return out;
  const QRectF window(0, 0, root->width(), root->height());
  check(root, window, {}, false, out);
  return out;
}

namespace {

void collect(QQuickItem* item, QStringList& out) {
  if (!item->isVisible() || item->opacity() <= 0.0) return;
  if (is_text(item) && !item->objectName().isEmpty())
    out << item->objectName() + QStringLiteral(": ") + item->property("text").toString();
  for (QQuickItem* child : item->childItems()) collect(child, out);
}

}  // namespace

QStringList named_texts(QQuickItem* root) {
  QStringList out;
  if (root) collect(root, out);
  return out;
}

bool write_status(const QString& path, QQuickItem* root) {
  QJsonObject texts;
  for (const QString& line : named_texts(root)) {
    const qsizetype colon = line.indexOf(QStringLiteral(": "));
    texts.insert(line.left(colon), line.mid(colon + 2));
  }
  QSaveFile f(path);
  if (!f.open(QIODevice::WriteOnly)) return false;
  f.write(QJsonDocument(QJsonObject{{QStringLiteral("texts"), texts}}).toJson(QJsonDocument::Compact));
  return f.commit();
}

bool drawn(const QImage& image) {
  if (image.isNull()) return false;
  const QImage img = image.convertToFormat(QImage::Format_ARGB32);
  QHash<QRgb, qsizetype> counts;
  for (int y = 0; y < img.height(); ++y) {
    const auto* row = reinterpret_cast<const QRgb*>(img.constScanLine(y));
    for (int x = 0; x < img.width(); ++x) ++counts[row[x]];
  }
  qsizetype most = 0;
  for (auto it = counts.cbegin(); it != counts.cend(); ++it) most = std::max(most, it.value());
  const qsizetype total = static_cast<qsizetype>(img.width()) * img.height();
  return total - most >= total / 50;
}

}  // namespace knoblab::ui
