// PLplot drawing for the discrepancy report (report_plot.hpp). One stream
// per file (plmkstrm … plend1), so a process can write any number of
// reports; the page setup is apps/fit's report's (fit::begin_page).
#include "report_plot.hpp"

#include "knoblab/fit/plplot_shared.hpp"

#include <plplot.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace knoblab::discovery::plot {

namespace fs = std::filesystem;

namespace {

constexpr PLINT kRed[kColorCount] = {255, 0, 175, 31, 200, 190};
constexpr PLINT kGreen[kColorCount] = {255, 0, 175, 119, 218, 30};
constexpr PLINT kBlue[kColorCount] = {255, 0, 175, 180, 242, 30};
constexpr PLINT kSolid = 1, kDashed = 3;  // pllsty

std::size_t utf8_length(const std::string& s) {
  std::size_t n = 0;
  for (const char c : s) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
  return n;
}

using fit::page_text;
using Metrics = fit::PageMetrics;

// Padded data range of the layers, or the panel's fixed one.
void ranges(const Panel& p, double& x0, double& x1, double& y0, double& y1) {
  x0 = y0 = std::numeric_limits<double>::infinity();
  x1 = y1 = -x0;
  for (const Layer& l : p.layers) {
    for (const double v : l.x)
      if (std::isfinite(v)) x0 = std::min(x0, v), x1 = std::max(x1, v);
    for (const double v : l.y)
      if (std::isfinite(v)) y0 = std::min(y0, v), y1 = std::max(y1, v);
  }
  auto pad = [](double& lo, double& hi, double f) {
    if (!(lo <= hi)) lo = -1.0, hi = 1.0;
    const double span = hi - lo > 0.0 ? hi - lo : std::max(1e-3, std::abs(hi) * 0.2);
    lo -= f * span;
    hi += f * span;
  };
  pad(x0, x1, 0.02);
  pad(y0, y1, 0.05);
  if (p.y_lo < p.y_hi) y0 = p.y_lo, y1 = p.y_hi;
}

void draw_layer(const Layer& l, const Metrics& m) {
  if (l.x.empty()) return;
  plcol0(l.color);
  plwidth(l.size * m.pen);
  pllsty(l.mark == Mark::Dashed ? kDashed : kSolid);
  std::vector<PLFLT> x(l.x.begin(), l.x.end()), y(l.y.begin(), l.y.end());
  const auto n = static_cast<PLINT>(x.size());
  switch (l.mark) {
    case Mark::Dots:
      // A zero-length line with cairo's round caps: a dot of the pen's size.
      if (m.vector) pl_cmd(PLESC_START_RASTERIZE, nullptr);
      plpoin(n, x.data(), y.data(), -1);
      if (m.vector) pl_cmd(PLESC_END_RASTERIZE, nullptr);
      break;
    case Mark::Line:
    case Mark::Dashed:
      plline(n, x.data(), y.data());
      break;
    case Mark::Stems:
      for (std::size_t i = 0; i < x.size(); ++i) pljoin(x[i], 0.0, x[i], y[i]);
      plwidth(2.5 * l.size * m.pen);
      plpoin(n, x.data(), y.data(), -1);
      break;
    case Mark::Fill: {
      for (std::size_t i = l.y_low.size(); i-- > 0;) x.push_back(l.x[i]), y.push_back(l.y_low[i]);
      plfill(static_cast<PLINT>(x.size()), x.data(), y.data());
      break;
    }
  }
  pllsty(kSolid);
}

// The legend in the column [x0, x1] right of the plot box, top aligned.
void draw_legend(const Panel& p, double x0, double x1, double vy0, double vy1, const Metrics& m) {
  std::vector<const Layer*> ls;
  for (const Layer& l : p.layers)
    if (!l.label.empty()) ls.push_back(&l);
  if (ls.empty()) return;
  const std::size_t n = ls.size();
  std::vector<PLINT> opt(n), text_colors(n, kBlack), colors(n), styles(n, kSolid),
      box_patterns(n, 0), symbol_numbers(n, 3);
  std::vector<PLFLT> widths(n), symbol_scales(n, 0.9), box_scales(n, 0.8), box_widths(n, 0.0);
  std::vector<const char*> text(n), symbols(n, "•");
  for (std::size_t k = 0; k < n; ++k) {
    const Layer& l = *ls[k];
    text[k] = l.label.c_str();
    colors[k] = l.color;
    widths[k] = std::max(1.0, l.size) * m.pen;
    styles[k] = l.mark == Mark::Dashed ? kDashed : kSolid;
    opt[k] = l.mark == Mark::Dots   ? PL_LEGEND_SYMBOL
             : l.mark == Mark::Fill ? PL_LEGEND_COLOR_BOX
                                    : PL_LEGEND_LINE;
  }
  PLFLT w = 0, h = 0;
  plvpor(x0, x1, vy0, vy1);
  plwind(0.0, 1.0, 0.0, 1.0);
  plwidth(m.pen);
  const double sample = 3.0 * m.char_mm / ((x1 - x0) * m.page_w_mm);  // symbol column
  pllegend(&w, &h, 0, PL_POSITION_TOP | PL_POSITION_LEFT | PL_POSITION_INSIDE, 0.0, 0.0, sample,
           kWhite, kWhite, kSolid, static_cast<PLINT>(n), 1, static_cast<PLINT>(n), opt.data(), 0.6,
           0.8, 2.0, 0.0, text_colors.data(), text.data(), colors.data(), box_patterns.data(),
           box_scales.data(), box_widths.data(), colors.data(), styles.data(), widths.data(),
           colors.data(), symbol_scales.data(), symbol_numbers.data(), symbols.data());
}

void draw_panel(const Panel& p, double vx0, double vx1, double vy0, double vy1, const Metrics& m) {
  double x0, x1, y0, y1;
  ranges(p, x0, x1, y0, y1);
  plvpor(vx0, vx1, vy0, vy1);
  plwind(x0, x1, y0, y1);
  for (const Layer& l : p.layers) draw_layer(l, m);
  plcol0(kBlack);
  plwidth(m.pen);
  plsxax(8, 0);  // plain numbers, no "(x10^-2)" where the headings are
  plsyax(8, 0);
  plbox("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
  plmtex("b", 2.7, 0.5, 0.5, p.xlabel.c_str());
  plmtex("l", 5.0, 0.5, 0.5, p.ylabel.c_str());
  plmtex("t", 1.2, 0.0, 0.0, p.heading.c_str());
}

// Greedy word wrap to about `chars` characters.
std::vector<std::string> wrap(const std::string& text, std::size_t chars) {
  const auto length = utf8_length;
  std::vector<std::string> lines;
  std::string line;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t sp = std::min(text.find(' ', at), text.size());
    const std::string word = text.substr(at, sp - at);
    if (!line.empty() && length(line) + 1 + length(word) > chars) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    at = sp + 1;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

// Lines of text from `y` down at `scale` × the page's text size, wrapped to
// the width (the cairo driver's sans averages about 0.7 character heights a
// character; wrapping a little early is harmless). Returns the next free y.
double draw_paragraphs(const std::vector<std::string>& paras, double y, double scale, double left,
                       double right, const Metrics& m) {
  plschr(0.0, scale * m.char_mm / m.def_mm);
  const double line = 1.9 * scale * m.char_mm / m.page_h_mm;
  const auto chars = static_cast<std::size_t>((right - left) * m.page_w_mm / (0.7 * scale * m.char_mm));
  for (const std::string& para : paras) {
    for (const std::string& l : wrap(para, chars)) {
      plptex(left, y, 1.0, 0.0, 0.0, l.c_str());
      y -= line;
    }
    y -= 0.5 * line;
  }
  plschr(0.0, m.char_mm / m.def_mm);
  return y;
}

// The table, the paragraphs and the notes, top down, in world units of the
// whole page. Header cells may hold '\n' (two lines).
void draw_text_page(const Page& page, const Metrics& m, double top) {
  const double left = 0.05, right = 0.95;
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  plcol0(kBlack);
  double y = top;
  if (!page.table.empty()) {
    const double scale = 0.85, line = 1.9 * scale * m.char_mm / m.page_h_mm;
    plschr(0.0, scale * m.char_mm / m.def_mm);
    // Column widths in proportion to their longest line, plus a gap.
    const std::size_t cols = page.table.front().size();
    std::vector<double> edge(cols, 0.0);  // right edges
    for (const auto& row : page.table) {
      for (std::size_t c = 0; c < row.size() && c < cols; ++c) {
        std::size_t at = 0;
        while (at <= row[c].size()) {
          const std::size_t nl = std::min(row[c].find('\n', at), row[c].size());
          edge[c] = std::max(edge[c], static_cast<double>(utf8_length(row[c].substr(at, nl - at))) + 3.0);
          at = nl + 1;
        }
      }
    }
    for (std::size_t c = 1; c < cols; ++c) edge[c] += edge[c - 1];
    auto right_edge = [&](std::size_t c) { return left + (right - left) * edge[c] / edge.back(); };
    for (std::size_t r = 0; r < page.table.size(); ++r) {
      std::size_t lines = 1;
      for (std::size_t c = 0; c < page.table[r].size() && c < cols; ++c) {
        std::size_t k = 0, at = 0;
        const std::string& cell = page.table[r][c];
        for (; at <= cell.size(); ++k) {
          const std::size_t nl = std::min(cell.find('\n', at), cell.size());
          const std::string text = cell.substr(at, nl - at);
          plptex(c == 0 ? left : right_edge(c), y - static_cast<double>(k) * line, 1.0, 0.0,
                 c == 0 ? 0.0 : 1.0, text.c_str());
          at = nl + 1;
        }
        lines = std::max(lines, k);
      }
      y -= static_cast<double>(lines - 1) * line;
      if (r == 0) {
        plwidth(m.pen);
        pljoin(left, y - 0.6 * line, right, y - 0.6 * line);
      }
      y -= line * (r == 0 ? 1.4 : 1.0);
    }
    plschr(0.0, m.char_mm / m.def_mm);
    y -= line;
  }
  y = draw_paragraphs(page.paragraphs, y, 1.0, left, right, m);
  draw_paragraphs(page.notes, y - 0.02, 0.8, left, right, m);
}

void draw_page(const Page& page, int width_px, int height_px, bool vector) {
  const Metrics m = fit::begin_page(width_px, height_px, vector);

  const double cw = m.char_mm / m.page_w_mm, ch = m.char_mm / m.page_h_mm;
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  plcol0(kBlack);
  page_text(1.5, 1.25, m, page.title);
  if (!page.subtitle.empty()) page_text(3.3, 0.85, m, page.subtitle);
  const double top = 1.0 - (page.subtitle.empty() ? 5.0 : 6.8) * ch;
  if (page.panels.empty()) {
    draw_text_page(page, m, top - 1.5 * ch);
    return;
  }

  const std::size_t cols = std::max<std::size_t>(1, page.columns);
  const std::size_t rows = (page.panels.size() + cols - 1) / cols;
  // The legend column: as wide as the longest label (the cairo driver's sans
  // is about 0.62 character heights a character) and its symbol.
  double legend_w = 0.0;
  for (const Panel& p : page.panels)
    for (const Layer& l : p.layers)
      if (page.legends && !l.label.empty())
        legend_w = std::max(legend_w, (0.62 * static_cast<double>(utf8_length(l.label)) + 5.0) * cw);
  const double left = 7.2 * cw, right = 1.0 - 1.5 * cw - legend_w, bottom = 4.0 * ch;
  const double vgap = 6.4 * ch, hgap = 9.0 * cw;
  const double h = (top - bottom - vgap * static_cast<double>(rows - 1)) / static_cast<double>(rows);
  const double w = (right - left - hgap * static_cast<double>(cols - 1)) / static_cast<double>(cols);
  for (std::size_t k = 0; k < page.panels.size(); ++k) {
    const double px = left + static_cast<double>(k % cols) * (w + hgap);
    const double py = top - static_cast<double>(k / cols) * (h + vgap);
    draw_panel(page.panels[k], px, px + w, py - h, py, m);
    if (legend_w > 0.0 && k % cols == cols - 1)
      draw_legend(page.panels[k], px + w + cw, px + w + cw + legend_w, py - h, py, m);
  }
}

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
  throw std::runtime_error("knoblab::discovery::write_discrepancy_report: cannot write " +
                           file.string() + ": " + why);
}

}  // namespace


void render(const Page& page, const fs::path& file, bool svg, int width_px, int height_px) {
  // Opened here: PLplot would prompt on stdin and exit() on a path it cannot
  // open. The driver closes it at plend1.
  std::FILE* fp = std::fopen(file.c_str(), "wb");
  if (fp == nullptr) fail(file, std::strerror(errno));
  PLINT previous = 0, stream = -1;
  plgstrm(&previous);
  plmkstrm(&stream);
  if (stream < 0) {
    std::fclose(fp);
    fail(file, "no free PLplot stream");
  }
  struct EndStream {
    PLINT previous;
    ~EndStream() {
      plend1();
      plsstrm(previous);
    }
  } end{previous};
  plsdev(svg ? "svgcairo" : "pngcairo");
  plsfile(fp);
  plspage(0.0, 0.0, width_px, height_px, 0, 0);
  plscmap0(kRed, kGreen, kBlue, kColorCount);
  plscolbg(255, 255, 255);
  plinit();
  draw_page(page, width_px, height_px, svg);
}

}  // namespace knoblab::discovery::plot
