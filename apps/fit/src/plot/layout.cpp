#include "knoblab/fit/plot/layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "knoblab/fit/plot/figure_options.hpp"
#include "knoblab/fit/plot/text.hpp"
#include "knoblab/fit/plot/ticks.hpp"

namespace knoblab::fit::plot {

namespace {

constexpr double kMargin = 2.5;     // mm, around the page
constexpr double kAscentEm = 0.93;  // capitals with an accent (θ̇) above the baseline
constexpr double kLineEm = 1.2;     // baseline to baseline
constexpr double kTick = 1.0, kTickGap = 0.8, kLabelGap = 1.2;
constexpr double kRowGap = 3.0, kColGap = 5.0, kLegendGap = 3.0, kHeadingGap = 1.2;
constexpr double kRuleMm = 0.2;
constexpr double kMinBoxMm = 12.0;

double em(double pt) { return pt * kPtMm; }
double cap(double pt) { return kCapHeightEm * em(pt); }
double line_height(double pt) { return (kAscentEm + kDescentEm) * em(pt); }

// Type sizes in points at 160 mm wide: 8.5 pt labels as a journal's
// full-width figure has them; a little smaller on a narrower page, larger
// on a wider one.
struct Sizes {
  double title, subtitle, heading, label, tick, legend, table, paragraph, note;
};
Sizes sizes(double width_mm, double scale) {
  const double s = scale * std::clamp(std::sqrt(width_mm / 160.0), 0.8, 1.3);
  return {10.0 * s, 8.0 * s, 8.5 * s, 8.5 * s, 7.5 * s, 7.5 * s, 7.5 * s, 8.0 * s, 7.0 * s};
}

// Lines of `ft` from `top` down, anchored at x; returns the y of their bottom.
double put_lines(std::vector<TextItem>& out, const FittedText& ft, double x, double top, Anchor a) {
  double y = top - kAscentEm * em(ft.size_pt);
  for (std::size_t k = 0; k < ft.lines.size(); ++k) {
    if (k > 0) y -= kLineEm * em(ft.size_pt);
    out.push_back({ft.lines[k], x, y, ft.size_pt, a, false});
  }
  return y - kDescentEm * em(ft.size_pt);
}

// The title and subtitle, centred; returns where the rest may begin.
double title_block(Layout& L, const Figure& fig, const Sizes& z) {
  const double width = L.width_mm - 2.0 * kMargin;
  double top = L.height_mm - kMargin;
  if (!fig.title.empty())
    top = put_lines(L.texts, fit_text(fig.title, width, z.title, 0.8 * z.title, 2), L.width_mm / 2, top,
                    Anchor::Middle);
  if (!fig.subtitle.empty())
    top = put_lines(L.texts, fit_text(fig.subtitle, width, z.subtitle, 0.8 * z.subtitle, 3),
                    L.width_mm / 2, top - 0.8, Anchor::Middle);
  return top - 2.5;
}

struct DataRange {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0;
  double y0 = x0, y1 = -x0;
  void add(double& lo, double& hi, double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
};

// The panel's window: the data padded (2 % in x, 5 % in y, as matplotlib
// pads), or the fixed y range.
void window(const Panel& p, PanelLayout& pl) {
  DataRange r;
  for (const Series& s : p.series) {
    for (const double v : s.x) r.add(r.x0, r.x1, v);
    if (s.mark == Mark::VLines) continue;
    for (const double v : s.y) r.add(r.y0, r.y1, v);
    for (const double v : s.y_low) r.add(r.y0, r.y1, v);
  }
  const Range x = padded(r.x0, r.x1, 0.02);
  Range y = padded(r.y0, r.y1, 0.05);
  if (p.y_from_zero && r.y0 >= 0.0 && r.y0 <= r.y1) y.lo = 0.0;
  if (p.y_lo < p.y_hi) y = {p.y_lo, p.y_hi};
  pl.x_lo = x.lo, pl.x_hi = x.hi, pl.y_lo = y.lo, pl.y_hi = y.hi;
}

double widest(const std::vector<std::string>& labels, double pt) {
  double w = 0.0;
  for (const std::string& l : labels) w = std::max(w, width_mm(l, pt));
  return w;
}

// X ticks for a box `w` mm wide: as many as fit with their labels apart.
Ticks x_ticks(const PanelLayout& pl, double w, double pt) {
  for (auto target = static_cast<std::size_t>(std::clamp(w / 20.0, 3.0, 8.0));; --target) {
    Ticks t = nice_ticks(pl.x_lo, pl.x_hi, target);
    const double spacing = w * t.step / (pl.x_hi - pl.x_lo);
    if (target <= 2 || widest(t.labels, pt) + 2.0 <= spacing) return t;
  }
}

Layout panel_layout(const Figure& fig, double W, double H, double scale) {
  Layout L;
  L.width_mm = W;
  L.height_mm = H;
  const Sizes z = sizes(W, scale);
  const double top = title_block(L, fig, z);
  const std::size_t n = fig.panels.size();
  const std::size_t cols = std::clamp<std::size_t>(fig.columns, 1, n);
  const std::size_t rows = (n + cols - 1) / cols;
  L.panels.resize(n);
  for (std::size_t i = 0; i < n; ++i) window(fig.panels[i], L.panels[i]);

  // Below a box: ticks, their labels, the axis label. Above: the heading.
  const double bottom_h = kTick + kTickGap + (kCapHeightEm + 0.05) * em(z.tick) + kLabelGap + line_height(z.label);
  const double min_head = cap(z.tick) / 2 + 0.8;  // the top y tick label's upper half
  const double one_line_head = line_height(z.heading) + kHeadingGap;
  const double rough_h = (top - kMargin - static_cast<double>(rows) * (one_line_head + bottom_h) -
                          static_cast<double>(rows - 1) * kRowGap) / static_cast<double>(rows);
  const auto y_target = static_cast<std::size_t>(std::clamp(std::round(rough_h / 9.0), 3.0, 7.0));
  std::vector<Ticks> yt(n);
  for (std::size_t i = 0; i < n; ++i) yt[i] = nice_ticks(L.panels[i].y_lo, L.panels[i].y_hi, y_target);

  // Widths: each column's y labels, the legend column after the last.
  std::vector<double> tick_w(cols, 0.0), left_w(cols, 0.0);
  for (std::size_t i = 0; i < n; ++i) tick_w[i % cols] = std::max(tick_w[i % cols], widest(yt[i].labels, z.tick));
  for (std::size_t c = 0; c < cols; ++c)
    left_w[c] = line_height(z.label) + kLabelGap + tick_w[c] + kTickGap + kTick;
  std::vector<std::vector<LegendEntry>> entries(n);
  double legend_pt = z.legend, legend_text = 0.0;
  const double sample_w = 5.5 * z.legend / 7.5;
  for (std::size_t i = cols - 1; i < n; i += cols) {
    entries[i] = legend_entries(fig.panels[i]);
    for (const LegendEntry& e : entries[i]) legend_text = std::max(legend_text, width_mm(e.label, legend_pt));
  }
  double legend_w = 0.0;
  if (legend_text > 0.0) {
    const double most = 0.4 * W - sample_w - kLabelGap;  // a legend never takes more than 40 %
    if (legend_text > most) legend_pt *= most / legend_text, legend_text = most;
    legend_w = kLegendGap + sample_w + kLabelGap + legend_text;
  }
  // The last x tick label may stand half out of its box.
  double overhang = 0.0;
  for (std::size_t i = cols - 1; i < n; i += cols)
    overhang = std::max(overhang, 0.5 * widest(nice_ticks(L.panels[i].x_lo, L.panels[i].x_hi, 6).labels, z.tick));
  const double right = std::max(legend_w, overhang);
  double w = W - 2.0 * kMargin - right - static_cast<double>(cols - 1) * kColGap;
  for (const double lw : left_w) w -= lw;
  w /= static_cast<double>(cols);

  // Headings fitted over their box (and the legend column beside the last),
  // all at the size the longest needs, so they match.
  std::vector<FittedText> heads(n);
  std::vector<double> head_h(rows, min_head);
  const auto heading_width = [&](std::size_t i) { return w + (i % cols == cols - 1 ? right : kColGap - 1.0); };
  double heading_pt = z.heading;
  for (std::size_t i = 0; i < n; ++i)
    if (!fig.panels[i].heading.empty())
      heading_pt = std::min(heading_pt, fit_text(fig.panels[i].heading, heading_width(i), z.heading, 0.8 * z.heading, 2).size_pt);
  for (std::size_t i = 0; i < n; ++i) {
    if (!fig.panels[i].heading.empty()) {
      heads[i] = fit_text(fig.panels[i].heading, heading_width(i), heading_pt, heading_pt, 2);
      const double lines = static_cast<double>(heads[i].lines.size());
      const double h = (kAscentEm + kDescentEm + (lines - 1.0) * kLineEm) * em(heads[i].size_pt) + kHeadingGap;
      head_h[i / cols] = std::max(head_h[i / cols], h);
    }
  }
  double h = top - kMargin - static_cast<double>(rows) * bottom_h - static_cast<double>(rows - 1) * kRowGap;
  for (const double hh : head_h) h -= hh;
  h /= static_cast<double>(rows);
  // Too little room for the data: all the type smaller.
  if ((h < kMinBoxMm || w < kMinBoxMm) && scale > 0.2) return panel_layout(fig, W, H, scale * 0.9);

  double y_top = top;
  for (std::size_t r = 0; r < rows; ++r) {
    double x_left = kMargin;
    for (std::size_t c = 0; c < cols && r * cols + c < n; ++c) {
      const std::size_t i = r * cols + c;
      const Panel& p = fig.panels[i];
      PanelLayout& pl = L.panels[i];
      pl.box = {x_left + left_w[c], y_top - head_h[r] - h, x_left + left_w[c] + w, y_top - head_h[r]};
      x_left = pl.box.x1 + kColGap;
      const Box& b = pl.box;
      if (!heads[i].lines.empty()) {
        const double lines = static_cast<double>(heads[i].lines.size());
        const double block = (kAscentEm + kDescentEm + (lines - 1.0) * kLineEm) * em(heads[i].size_pt);
        put_lines(L.texts, heads[i], b.x0, b.y1 + kHeadingGap + block, Anchor::Start);
      }
      // Frame and ticks (outwards, as matplotlib's).
      L.rules.push_back({b.x0, b.y0, b.x1, b.y0, kRuleMm});
      L.rules.push_back({b.x1, b.y0, b.x1, b.y1, kRuleMm});
      L.rules.push_back({b.x1, b.y1, b.x0, b.y1, kRuleMm});
      L.rules.push_back({b.x0, b.y1, b.x0, b.y0, kRuleMm});
      const Ticks xt = x_ticks(pl, w, z.tick);
      const double x_label_base = b.y0 - kTick - kTickGap - cap(z.tick);
      for (std::size_t k = 0; k < xt.at.size(); ++k) {
        const double x = b.x0 + (xt.at[k] - pl.x_lo) / (pl.x_hi - pl.x_lo) * w;
        L.rules.push_back({x, b.y0, x, b.y0 - kTick, kRuleMm});
        L.texts.push_back({xt.labels[k], x, x_label_base, z.tick, Anchor::Middle, false});
      }
      for (std::size_t k = 0; k < yt[i].at.size(); ++k) {
        const double y = b.y0 + (yt[i].at[k] - pl.y_lo) / (pl.y_hi - pl.y_lo) * h;
        L.rules.push_back({b.x0, y, b.x0 - kTick, y, kRuleMm});
        L.texts.push_back({yt[i].labels[k], b.x0 - kTick - kTickGap, y - cap(z.tick) / 2, z.tick, Anchor::End, false});
      }
      if (!p.xlabel.empty()) {
        const FittedText ft = fit_text(p.xlabel, w, z.label, 0.6 * z.label, 1);
        const double base = x_label_base - 0.05 * em(z.tick) - kLabelGap - kAscentEm * em(ft.size_pt);
        L.texts.push_back({ft.lines.front(), (b.x0 + b.x1) / 2, base, ft.size_pt, Anchor::Middle, false});
      }
      if (!p.ylabel.empty()) {
        const FittedText ft = fit_text(p.ylabel, h, z.label, 0.5 * z.label, 1);
        const double base = b.x0 - kTick - kTickGap - tick_w[c] - kLabelGap - kDescentEm * em(ft.size_pt);
        L.texts.push_back({ft.lines.front(), base, (b.y0 + b.y1) / 2, ft.size_pt, Anchor::Middle, true});
      }
      // The legend, top aligned with the box, rows shrunk to its height.
      const std::vector<LegendEntry>& es = entries[i];
      if (!es.empty()) {
        // Rows 1.6 em apart: room for a subscript above the next row's capitals.
        double pt = legend_pt, row = 1.6 * em(pt);
        if (row * static_cast<double>(es.size()) > h) {
          row = h / static_cast<double>(es.size());
          pt = std::min(pt, row / (1.6 * kPtMm));
        }
        const double x0 = b.x1 + kLegendGap;
        for (std::size_t k = 0; k < es.size(); ++k) {
          const double cy = b.y1 - (static_cast<double>(k) + 0.5) * row;
          const double half = std::min(0.33 * row, 1.2);
          pl.legend.push_back({es[k], {x0, cy - half, x0 + sample_w, cy + half}});
          L.texts.push_back({es[k].label, x0 + sample_w + kLabelGap, cy - cap(pt) / 2, pt, Anchor::Start, false});
        }
      }
    }
    y_top -= head_h[r] + h + bottom_h + kRowGap;
  }
  return L;
}

// The table, paragraphs and notes of a text page from `top` down at `f`
// times their type sizes; returns the y where they end.
double text_block(Layout& L, const TextPage& page, const Sizes& z, double f, double top) {
  const double left = kMargin, right = L.width_mm - kMargin, width = right - left;
  double y = top;
  if (!page.table.empty()) {
    double pt = z.table * f;
    const std::size_t cols = page.table.front().size();
    const auto cell_lines = [](const std::string& cell) {
      std::vector<std::string> out;
      std::size_t at = 0;
      while (at <= cell.size()) {
        const std::size_t nl = std::min(cell.find('\n', at), cell.size());
        out.push_back(cell.substr(at, nl - at));
        at = nl + 1;
      }
      return out;
    };
    std::vector<double> col_w(cols, 0.0);
    for (const auto& row : page.table)
      for (std::size_t c = 0; c < row.size() && c < cols; ++c)
        for (const std::string& l : cell_lines(row[c])) col_w[c] = std::max(col_w[c], width_mm(l, 1.0));
    const double gap = 3.0;
    double sum = 0.0;
    for (const double cw : col_w) sum += cw;
    // The table at its size, or smaller until it fits the width.
    if (sum * pt + gap * static_cast<double>(cols - 1) > width)
      pt = (width - gap * static_cast<double>(cols - 1)) / sum;
    std::vector<double> edge(cols);
    double x = left;
    for (std::size_t c = 0; c < cols; ++c) {
      x += col_w[c] * pt + (c > 0 ? gap : 0.0);
      edge[c] = x;
    }
    const double scale_gap = (right - x) / static_cast<double>(std::max<std::size_t>(1, cols - 1));
    for (std::size_t c = 1; c < cols; ++c) edge[c] += scale_gap * static_cast<double>(c);  // spread to the width
    const double line = kLineEm * em(pt);
    for (std::size_t r = 0; r < page.table.size(); ++r) {
      std::size_t lines = 1;
      for (std::size_t c = 0; c < page.table[r].size() && c < cols; ++c) {
        const auto ls = cell_lines(page.table[r][c]);
        lines = std::max(lines, ls.size());
        for (std::size_t k = 0; k < ls.size(); ++k) {
          const double base = y - kAscentEm * em(pt) - static_cast<double>(k) * line;
          L.texts.push_back({ls[k], c == 0 ? left : edge[c], base, pt, c == 0 ? Anchor::Start : Anchor::End, false});
        }
      }
      y -= static_cast<double>(lines) * line;
      if (r == 0) {
        L.rules.push_back({left, y - 0.3 * line, right, y - 0.3 * line, kRuleMm});
        y -= 0.5 * line;
      }
    }
    y -= line;
  }
  const auto paragraphs = [&](const std::vector<std::string>& paras, double pt) {
    for (const std::string& p : paras) {
      y = put_lines(L.texts, {wrap(p, width, pt), pt}, left, y, Anchor::Start);
      y -= 0.5 * kLineEm * em(pt);
    }
  };
  paragraphs(page.paragraphs, z.paragraph * f);
  y -= 1.5;
  paragraphs(page.notes, z.note * f);
  return y;
}

Layout text_layout(const Figure& fig, double W, double H) {
  const Sizes z = sizes(W, 1.0);
  if (H <= 0.0) {  // as tall as the text at its size
    Layout probe;
    probe.width_mm = W;
    probe.height_mm = 10.0 * kMaxSideMm;
    const double top = title_block(probe, fig, z);
    const double bottom = text_block(probe, fig.text, z, 1.0, top);
    H = std::clamp(probe.height_mm - bottom + kMargin + 1.0, kMinSideMm, 1.5 * W);
  }
  for (double f = 1.0;; f *= 0.95) {
    Layout L;
    L.width_mm = W;
    L.height_mm = H;
    const double top = title_block(L, fig, z);
    if (text_block(L, fig.text, z, f, top) >= kMargin || f < 0.2) return L;
  }
}

}  // namespace

Box extent(const TextItem& t) {
  const double along = width_mm(t.text, t.size_pt);
  const double start = t.anchor == Anchor::Start ? 0.0 : t.anchor == Anchor::Middle ? -along / 2 : -along;
  const double up = kAscentEm * em(t.size_pt), down = kDescentEm * em(t.size_pt);
  if (t.vertical) return {t.x - up, t.y + start, t.x + down, t.y + start + along};
  return {t.x + start, t.y - down, t.x + start + along, t.y + up};
}

Layout layout_figure(const Figure& fig, double width_mm, double height_mm) {
  if (fig.panels.empty()) return text_layout(fig, width_mm, height_mm);
  const std::size_t cols = std::max<std::size_t>(1, fig.columns);
  const std::size_t rows = (fig.panels.size() + cols - 1) / cols;
  const double h = height_mm > 0.0 ? height_mm : default_height_mm(rows, width_mm);
  return panel_layout(fig, width_mm, h, 1.0);
}

}  // namespace knoblab::fit::plot
