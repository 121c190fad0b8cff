#include "design_variant.hpp"

#include <QString>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "knoblab/design/curve.hpp"

namespace knoblab::ui {

namespace {

QVariantMap point(double x, double y) { return {{QStringLiteral("x"), x}, {QStringLiteral("y"), y}}; }

double peak(const design::Waveform& w) {
  double p = 0.0;
  for (const design::Point& q : w.points) p = std::max(p, std::abs(q.y));
  return p;
}

QString name_of(design::Channel c) { return QString::fromUtf8(design::channel_name(c).data(), static_cast<qsizetype>(design::channel_name(c).size())); }

QVariantMap tile_variant(const design::Tile& t) {
  return {{QStringLiteral("name"), QString::fromStdString(t.name)},
          {QStringLiteral("drawnFor"), name_of(t.drawn_for)},
          {QStringLiteral("peak"), peak(t.waveform)},
          {QStringLiteral("thumb"), thumb_variant(t.waveform)}};
}

}  // namespace

QVariantList points_variant(const design::Waveform& w) {
  QVariantList out;
  for (const design::Point& p : w.points) out.append(point(p.x, p.y));
  return out;
}

QVariantList curve_variant(const design::Waveform& w, double from, double to, int n) {
  QVariantList out;
  if (design::waveform_problem(w) != "" || n < 1 || !(to > from)) return out;
  const model::CubicSpline s = design::spline_of(w);
  for (int i = 0; i <= n; ++i) {
    const double x = from + (to - from) * i / n;
    out.append(point(x, design::value_at(s, x)));
  }
  return out;
}

QVariantList thumb_variant(const design::Waveform& w) {
  constexpr int kSamples = 48;
  const double p = peak(w);
  QVariantList curve = curve_variant(w, w.x_min(), w.x_max(), kSamples);
  const double span = w.x_max() - w.x_min();
  for (QVariant& v : curve) {
    QVariantMap m = v.toMap();
    m[QStringLiteral("x")] = (m.value(QStringLiteral("x")).toDouble() - w.x_min()) / span;
    m[QStringLiteral("y")] = p > 0.0 ? m.value(QStringLiteral("y")).toDouble() / p : 0.0;
    v = m;
  }
  return curve;
}

QVariantList palette_variant(const design::Design& d) {
  QVariantList tabs;
  for (const design::PaletteTab& tab : d.palette) {
    QVariantList tiles;
    for (const design::Tile& t : tab.tiles) tiles.append(tile_variant(t));
    tabs.append(QVariantMap{{QStringLiteral("name"), QString::fromStdString(tab.name)}, {QStringLiteral("tiles"), tiles}});
  }
  return tabs;
}

QVariantList channels_variant(const design::Design& d) {
  QVariantList channels;
  for (const design::Channel c : design::kChannels) {
    QVariantList lines;
    for (const design::Line& line : d.lines(c).lines) {
      QVariantList tiles;
      for (const design::PlacedTile& p : line.tiles) {
        QVariantMap t = tile_variant(p.tile);
        t[QStringLiteral("from")] = p.from;
        t[QStringLiteral("to")] = p.to;
        tiles.append(t);
      }
      lines.append(QVariantMap{{QStringLiteral("active"), line.active}, {QStringLiteral("tiles"), tiles}});
    }
    channels.append(QVariantMap{{QStringLiteral("name"), name_of(c)},
                                {QStringLiteral("play"), d.lines(c).play},
                                {QStringLiteral("lines"), lines}});
  }
  return channels;
}

design::Channel channel_of(const QString& name) {
  for (const design::Channel c : design::kChannels)
    if (name == name_of(c)) return c;
  throw std::invalid_argument("no channel called " + name.toStdString());
}

}  // namespace knoblab::ui
