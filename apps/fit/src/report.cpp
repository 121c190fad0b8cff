// Fit reports drawn with PLplot (thesis Figures 17–19 and 22–34).
//
// Every file is one PLplot stream of its own (plmkstrm … plend1), so a
// process can write any number of reports; PLplot keeps global state and is
// not thread-safe, so one mutex serializes write_report.
//
// Look of the plots (the thesis' figures): raw torque as a light gray point
// cloud, the fit in black, the 95% band of the fitted curve dashed. A band is
// a few hundredths of a mN·m on a plot spanning tens, thinner than its line,
// so every page also has a residual panel (raw − fitted) on the residuals'
// own scale, where the bands are shaded: the curve's band dark blue, the
// observation band light blue. The total
// torque against θ or θ̇ is not a function of that axis (it depends on all of
// θ, θ̇, θ̈), so fitted τ and its band are drawn as points there; the parts
// τ_pos(θ) and τ_vel(θ̇) are functions, so they are drawn as lines through the
// samples sorted by the axis. Their band half-widths come from the whole
// model's band (Prediction::curve_half, which varies with all three
// kinematic variables), averaged over neighbouring samples along the axis so
// the dashed line is a curve rather than noise.
#include "knoblab/fit/report.hpp"
#include "knoblab/fit/plplot_shared.hpp"
#include "knoblab/model/quantile.hpp"

#include <plplot.h>

#include <algorithm>
#include <iterator>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace knoblab::fit {
namespace {

namespace fs = std::filesystem;

constexpr double kmNm = 1e3;  // N·m → mN·m, at the edge only

// cmap0 entries.
enum : PLINT {
  kWhite = 0,
  kBlack = 1,
  kCloud = 2,     // raw data
  kBandDots = 3,  // band drawn as points (total τ panels)
  kObs = 4,       // observation band
  kStick = 5,     // stick band limits
  kCurveFill = 6,  // shaded 95% band of the fitted curve
  kObsFill = 7,    // shaded 95% observation band
  kColorCount = 8
};
constexpr PLINT kRed[kColorCount] = {255, 0, 190, 105, 120, 150, 60, 200};
constexpr PLINT kGreen[kColorCount] = {255, 0, 190, 105, 120, 150, 100, 218};
constexpr PLINT kBlue[kColorCount] = {255, 0, 190, 105, 120, 150, 190, 242};

// PLplot's built-in line styles (pllsty): 1 solid, 2 1 mm dashes, 3 2 mm dashes.
// 4: long dashes, short gaps (the stick band's limits).
constexpr PLINT kSolid = 1, kDotted = 2, kDashed = 3, kLongDash = 4;

enum class Mark { Dots, Line, Dashed, Dotted, LongDash, Fill };

struct Layer {
  std::string label;  // empty: not in the legend
  Mark mark = Mark::Dots;
  PLINT color = kBlack;
  double size = 1.0;    // dot diameter or line width, in pen widths
  int legend_rank = 0;  // legend order (ties keep drawing order)
  std::vector<PLFLT> x, y;
  std::vector<PLFLT> y_low;  // Fill: the area between y_low and y
};

struct Panel {
  std::string heading, xlabel, ylabel;
  std::vector<Layer> layers;  // drawn in this order
  std::vector<double> vlines;  // vertical long-dashed lines (stick band limits)
  std::string vline_label;
  bool y_from_zero = false;
  double y_limit = 0.0;  // > 0: y axis fixed at ±y_limit (what lies beyond is cut)
};

struct Page {
  std::string title, subtitle;
  std::vector<Panel> panels;  // stacked top to bottom
};

// ---------------------------------------------------------------- data prep

// m indices spread evenly over [0, n).
std::vector<std::size_t> thin(std::size_t n, std::size_t m) {
  std::vector<std::size_t> idx;
  if (n <= m) {
    idx.resize(n);
    std::iota(idx.begin(), idx.end(), std::size_t{0});
    return idx;
  }
  idx.reserve(m);
  for (std::size_t k = 0; k < m; ++k) {
    idx.push_back(static_cast<std::size_t>(static_cast<double>(k) * static_cast<double>(n) /
                                           static_cast<double>(m)));
  }
  return idx;
}

std::vector<std::size_t> sorted_by(const std::vector<double>& key) {
  std::vector<std::size_t> order(key.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  return order;
}

// Centered moving average of v taken in the given order (window ≈ n/200),
// over the finite values only (NaN where a window has none).
std::vector<double> smoothed_along(const std::vector<double>& v,
                                   const std::vector<std::size_t>& order) {
  const std::size_t n = order.size();
  std::vector<double> prefix(n + 1, 0.0);
  std::vector<std::size_t> finite(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const double x = v[order[k]];
    const bool ok = std::isfinite(x);
    prefix[k + 1] = prefix[k] + (ok ? x : 0.0);
    finite[k + 1] = finite[k] + (ok ? 1 : 0);
  }
  const std::size_t half = std::max<std::size_t>(1, n / 400);
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k >= half ? k - half : 0;
    const std::size_t hi = std::min(n, k + half + 1);
    const std::size_t count = finite[hi] - finite[lo];
    out[k] = count == 0 ? std::numeric_limits<double>::quiet_NaN()
                        : (prefix[hi] - prefix[lo]) / static_cast<double>(count);
  }
  return out;  // in `order`'s positions
}

// A time series reduced to at most 2·buckets vertices that keep its
// envelope: the smallest and the largest value of each bucket, in time order
// (plain striding would alias a fast signal into false beats).
template <typename YFn>
void minmax_series(Layer& l, const std::vector<double>& t, std::size_t buckets, double yscale,
                   YFn y) {
  const std::size_t n = t.size();
  if (n <= 2 * buckets) {
    for (std::size_t i = 0; i < n; ++i) {
      l.x.push_back(t[i]);
      l.y.push_back(yscale * y(i));
    }
    return;
  }
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t lo = b * n / buckets, hi = (b + 1) * n / buckets;
    std::size_t imin = hi, imax = hi;
    for (std::size_t i = lo; i < hi; ++i) {
      if (!std::isfinite(y(i))) continue;
      if (imin == hi || y(i) < y(imin)) imin = i;
      if (imax == hi || y(i) > y(imax)) imax = i;
    }
    if (imin == hi) continue;  // nothing finite in this bucket
    for (const std::size_t i : {std::min(imin, imax), std::max(imin, imax)}) {
      l.x.push_back(t[i]);
      l.y.push_back(yscale * y(i));
    }
  }
}

// A band's edge over time: the largest y(i) of each bucket at the bucket's
// middle, so a fast-varying band is shown by its envelope.
template <typename YFn>
void envelope_series(Layer& l, const std::vector<double>& t, std::size_t buckets, double yscale,
                     YFn y) {
  const std::size_t n = t.size();
  buckets = std::min(buckets, n);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t lo = b * n / buckets, hi = (b + 1) * n / buckets;
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t i = lo; i < hi; ++i)
      if (std::isfinite(y(i))) top = std::max(top, y(i));
    l.x.push_back(t[(lo + hi - 1) / 2]);
    l.y.push_back(std::isfinite(top) ? yscale * top : std::numeric_limits<double>::quiet_NaN());
  }
}

// Points (x[i], y(i)) for the given sample indices, scaled to presentation units.
template <typename YFn>
Layer points(std::string label, PLINT color, double size, int rank, const std::vector<double>& x,
             const std::vector<std::size_t>& idx, double yscale, YFn y) {
  Layer l;
  l.label = std::move(label);
  l.mark = Mark::Dots;
  l.color = color;
  l.size = size;
  l.legend_rank = rank;
  l.x.reserve(idx.size());
  l.y.reserve(idx.size());
  for (const std::size_t i : idx) {
    l.x.push_back(x[i]);
    l.y.push_back(yscale * y(i));
  }
  return l;
}

Layer curve(std::string label, Mark mark, PLINT color, double width, int rank) {
  Layer l;
  l.label = std::move(label);
  l.mark = mark;
  l.color = color;
  l.size = width;
  l.legend_rank = rank;
  return l;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// ----------------------------------------------------------------- drawing

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  // Padded by `pad` of the span; a degenerate range gets a sensible width.
  Range padded(double pad) const {
    Range r = *this;
    if (!(r.lo <= r.hi)) return {-1.0, 1.0};
    double span = r.hi - r.lo;
    if (span <= 1e-12 * std::max(1.0, std::abs(r.hi))) {
      span = std::max(std::abs(r.hi) * 0.2, 1e-3);
      r.lo -= span / 2;
      r.hi += span / 2;
      return r;
    }
    r.lo -= pad * span;
    r.hi += pad * span;
    return r;
  }
};

// Sizes derived from the page so text and marks scale with the image.
using Metrics = PageMetrics;

// Non-finite values (a band whose covariance failed, say) are left out:
// points are dropped, lines are broken there.
// A filled band: one polygon per run of finite vertices, upper edge forward
// and lower edge back.
void draw_fill(const Layer& l) {
  plcol0(l.color);
  std::vector<PLFLT> x, y;
  std::size_t start = 0;
  auto polygon = [&](std::size_t end) {
    x.clear();
    y.clear();
    for (std::size_t i = start; i < end; ++i) x.push_back(l.x[i]), y.push_back(l.y[i]);
    for (std::size_t i = end; i-- > start;) x.push_back(l.x[i]), y.push_back(l.y_low[i]);
    if (x.size() >= 4) plfill(static_cast<PLINT>(x.size()), x.data(), y.data());
  };
  for (std::size_t i = 0; i < l.x.size(); ++i) {
    if (std::isfinite(l.x[i]) && std::isfinite(l.y[i]) && std::isfinite(l.y_low[i])) continue;
    polygon(i);
    start = i + 1;
  }
  polygon(l.x.size());
}

void draw_layer(const Layer& l, const Metrics& m) {
  if (l.x.empty()) return;
  if (l.mark == Mark::Fill) {
    draw_fill(l);
    return;
  }
  plcol0(l.color);
  plwidth(l.size * m.pen);
  switch (l.mark) {
    case Mark::Dots: pllsty(kSolid); break;
    case Mark::Line: pllsty(kSolid); break;
    case Mark::Dashed: pllsty(kDashed); break;
    case Mark::Dotted: pllsty(kDotted); break;
    case Mark::LongDash: pllsty(kLongDash); break;
    case Mark::Fill: break;
  }
  std::vector<PLFLT> x, y;
  x.reserve(l.x.size());
  y.reserve(l.y.size());
  auto flush = [&] {
    if (x.empty()) return;
    const PLINT n = static_cast<PLINT>(x.size());
    if (l.mark == Mark::Dots) {
      // A zero-length line with the cairo driver's round caps: a dot of the
      // pen's diameter, far cheaper than a glyph per point.
      plpoin(n, x.data(), y.data(), -1);
    } else if (n > 1) {
      plline(n, x.data(), y.data());
    }
    x.clear();
    y.clear();
  };
  for (std::size_t i = 0; i < l.x.size(); ++i) {
    if (std::isfinite(l.x[i]) && std::isfinite(l.y[i])) {
      x.push_back(l.x[i]);
      y.push_back(l.y[i]);
    } else if (l.mark != Mark::Dots) {
      flush();
    }
  }
  flush();
  pllsty(kSolid);
}

// Layers in order; in SVG each run of point layers goes into one embedded
// raster image (tens of thousands of <path> elements make an SVG no viewer
// opens comfortably). Lines, axes and text stay vectors.
void draw_layers(const std::vector<Layer>& layers, const Metrics& m) {
  bool rastering = false;
  for (const Layer& l : layers) {
    const bool dots = l.mark == Mark::Dots && !l.x.empty();
    if (m.vector && dots != rastering) {
      pl_cmd(dots ? PLESC_START_RASTERIZE : PLESC_END_RASTERIZE, nullptr);
      rastering = dots;
    }
    draw_layer(l, m);
  }
  if (rastering) pl_cmd(PLESC_END_RASTERIZE, nullptr);
}

struct LegendEntry {
  std::string text;
  Mark mark;
  PLINT color;
  double size;
  int rank;
};

std::vector<LegendEntry> legend_entries(const Panel& panel) {
  std::vector<LegendEntry> entries;
  for (const Layer& l : panel.layers) {
    if (!l.label.empty()) entries.push_back({l.label, l.mark, l.color, l.size, l.legend_rank});
  }
  if (!panel.vlines.empty() && !panel.vline_label.empty())
    entries.push_back({panel.vline_label, Mark::LongDash, kStick, 1.2, 100});
  std::stable_sort(entries.begin(), entries.end(),
                   [](const LegendEntry& a, const LegendEntry& b) { return a.rank < b.rank; });
  return entries;
}

constexpr double kLegendTextScale = 0.85;
constexpr double kLegendSampleChars = 3.2;  // width of the line/symbol samples

// The legend in the column [x0, x1] right of the plot box, top aligned with
// the box, at the column's left edge. Returns its width as a page fraction
// (PLplot measures the text with the device's fonts). `ink` false draws it
// white on the white page: how the legends are measured before the layout.
double draw_legend(const Panel& panel, double x0, double x1, double vy0, double vy1,
                   const Metrics& m, bool ink) {
  const std::vector<LegendEntry> entries = legend_entries(panel);
  if (entries.empty()) return 0.0;
  const std::size_t n = entries.size();
  std::vector<PLINT> opt(n), text_colors(n, ink ? kBlack : kWhite), line_colors(n),
      line_styles(n), symbol_colors(n), symbol_numbers(n, 3);
  std::vector<PLINT> box_colors(n, kWhite), box_patterns(n, 0);
  std::vector<PLFLT> line_widths(n), symbol_scales(n), box_scales(n, 0.9), box_widths(n, 0.0);
  std::vector<const char*> text(n), symbols(n, "•");
  for (std::size_t k = 0; k < n; ++k) {
    const LegendEntry& e = entries[k];
    text[k] = e.text.c_str();
    line_colors[k] = symbol_colors[k] = ink ? e.color : kWhite;
    line_widths[k] = std::max(1.0, e.size) * m.pen;
    symbol_scales[k] = e.color == kCloud ? 1.0 : 0.75;
    switch (e.mark) {
      case Mark::Dots: opt[k] = PL_LEGEND_SYMBOL; line_styles[k] = kSolid; break;
      case Mark::Line: opt[k] = PL_LEGEND_LINE; line_styles[k] = kSolid; break;
      case Mark::Dashed: opt[k] = PL_LEGEND_LINE; line_styles[k] = kDashed; break;
      case Mark::Dotted: opt[k] = PL_LEGEND_LINE; line_styles[k] = kDotted; break;
      case Mark::LongDash: opt[k] = PL_LEGEND_LINE; line_styles[k] = kLongDash; break;
      case Mark::Fill:
        opt[k] = PL_LEGEND_COLOR_BOX;
        line_styles[k] = kSolid;
        box_colors[k] = ink ? e.color : kWhite;
        break;
    }
  }
  plvpor(x0, x1, vy0, vy1);
  plwind(0.0, 1.0, 0.0, 1.0);
  const double sample = kLegendSampleChars * m.char_mm / ((x1 - x0) * m.page_w_mm);
  PLFLT lw = 0, lh = 0;
  pllsty(kSolid);
  plwidth(m.pen);
  pllegend(&lw, &lh, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
           PL_POSITION_TOP | PL_POSITION_LEFT | PL_POSITION_INSIDE | PL_POSITION_VIEWPORT, 0.0,
           0.0, sample, kWhite, ink ? kBlack : kWhite, kSolid, 0, 0, static_cast<PLINT>(n),
           opt.data(), 0.8, kLegendTextScale, 2.3, 0.0, text_colors.data(), text.data(),
           box_colors.data(), box_patterns.data(), box_scales.data(), box_widths.data(),
           line_colors.data(), line_styles.data(), line_widths.data(),
           symbol_colors.data(), symbol_scales.data(), symbol_numbers.data(), symbols.data());
  return lw * (x1 - x0);
}

void draw_panel(const Panel& panel, double vx0, double vx1, double vy0, double vy1,
                const Metrics& m) {
  Range xr, yr;
  for (const Layer& l : panel.layers) {
    for (const double v : l.x) xr.add(v);
    for (const double v : l.y) yr.add(v);
  }
  for (const double v : panel.vlines) xr.add(v);
  xr = xr.padded(0.02);
  const bool from_zero = panel.y_from_zero && yr.lo >= 0.0;
  yr = yr.padded(0.05);
  if (from_zero) yr.lo = 0.0;
  if (panel.y_limit > 0.0) yr = {-panel.y_limit, panel.y_limit};

  plvpor(vx0, vx1, vy0, vy1);
  plwind(xr.lo, xr.hi, yr.lo, yr.hi);

  draw_layers(panel.layers, m);
  for (const double v : panel.vlines) {
    Layer l = curve("", Mark::LongDash, kStick, 1.2, 0);
    l.x = {v, v};
    l.y = {yr.lo, yr.hi};
    draw_layer(l, m);
  }

  // The box last, so data never paints over the axes.
  plcol0(kBlack);
  pllsty(kSolid);
  plwidth(m.pen);
  // Plain numbers: PLplot would otherwise move a "(x10^-2)" scale above
  // the axis, where the headings are.
  plsxax(8, 0);
  plsyax(8, 0);
  plbox("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
  plmtex("b", 2.7, 0.5, 0.5, panel.xlabel.c_str());
  plmtex("l", 5.4, 0.5, 0.5, panel.ylabel.c_str());
  if (!panel.heading.empty()) plmtex("t", 1.5, 0.0, 0.0, panel.heading.c_str());
}

void draw_page(const Page& page, const ReportOptions& opt, bool vector) {
  const Metrics m = begin_page(opt.width_px, opt.height_px, vector);

  // Layout in character heights, converted to page fractions.
  const double cw = m.char_mm / m.page_w_mm, ch = m.char_mm / m.page_h_mm;
  const double left = 7.6 * cw;
  const double page_right = 1.0 - 1.0 * cw;
  const double top = 1.0 - (page.subtitle.empty() ? 5.0 : 6.8) * ch;
  const double bottom = 4.0 * ch;
  const double gap = 6.6 * ch;  // x label of one panel + heading of the next

  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  plcol0(kBlack);
  page_text(1.5, 1.25, m, page.title);
  if (!page.subtitle.empty()) page_text(3.3, 0.85, m, page.subtitle);

  const std::size_t np = page.panels.size();
  const double h = (top - bottom - gap * static_cast<double>(np - 1)) / static_cast<double>(np);
  auto panel_top = [&](std::size_t k) { return top - static_cast<double>(k) * (h + gap); };

  // Legends are measured first (drawn white on white): the widest decides
  // where the plot boxes end. It never takes more than 45% of the width.
  double legend_w = 0.0;
  for (std::size_t k = 0; k < np; ++k) {
    const double w = draw_legend(page.panels[k], 0.0, page_right, panel_top(k) - h, panel_top(k),
                                 m, false);
    legend_w = std::max(legend_w, w);
  }
  legend_w = std::min(0.45, legend_w);
  const double right = page_right - legend_w - (legend_w > 0.0 ? 2.0 * cw : 0.0);

  for (std::size_t k = 0; k < np; ++k) {
    draw_panel(page.panels[k], left, right, panel_top(k) - h, panel_top(k), m);
    draw_legend(page.panels[k], page_right - legend_w, page_right, panel_top(k) - h,
                panel_top(k), m, true);
  }
}

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
  throw std::runtime_error("knoblab::fit::write_report: cannot write " + file.string() + ": " +
                           why);
}

// One file, one PLplot stream. The file is opened here (PLplot would prompt on
// stdin and then exit() on a path it cannot open) and handed over; the
// driver closes it at plend1.
void render(const Page& page, const fs::path& file, const char* device, bool vector,
            const ReportOptions& opt) {
  std::FILE* fp = std::fopen(file.c_str(), "wb");
  if (fp == nullptr) fail(file, std::strerror(errno));

  PLINT previous = 0;
  plgstrm(&previous);
  PLINT stream = -1;
  plmkstrm(&stream);
  if (stream < 0) {
    std::fclose(fp);
    fail(file, "no free PLplot stream");
  }
  struct EndStream {
    PLINT previous;
    ~EndStream() {
      plend1();  // also frees the stream and selects stream 0
      plsstrm(previous);
    }
  } end{previous};

  plsdev(device);
  plsfile(fp);  // the driver owns and closes it from here
  plspage(0.0, 0.0, opt.width_px, opt.height_px, 0, 0);
  plscmap0(kRed, kGreen, kBlue, kColorCount);
  plscolbg(255, 255, 255);
  plinit();
  draw_page(page, opt, vector);
}

// ------------------------------------------------------------------- pages

struct Inputs {
  const FitResult& r;
  const FitData& d;
  const Prediction& p;
  const ReportOptions& opt;
  std::size_t n;
  bool has_obs;
};

// Raw and fitted total torque against x (θ or θ̇): the top panels.
Panel total_panel(const Inputs& in, const std::vector<double>& x, const std::string& xlabel) {
  Panel panel;
  panel.heading = "All torques";
  panel.xlabel = xlabel;
  panel.ylabel = "#gt (mN·m)";
  const auto cloud = thin(in.n, in.opt.max_points);
  const auto fitted = thin(in.n, std::max<std::size_t>(1, in.opt.max_points / 2));
  const auto& p = in.p;
  panel.layers.push_back(points("raw #gt", kCloud, 2.2, 0, x, cloud, kmNm,
                                [&](std::size_t i) { return in.d.torque[i]; }));
  panel.layers.push_back(points("95% band", kBandDots, 1.0, 2, x, fitted, kmNm,
                                [&](std::size_t i) { return p.tau[i] + p.curve_half[i]; }));
  panel.layers.push_back(points("", kBandDots, 1.0, 2, x, fitted, kmNm,
                                [&](std::size_t i) { return p.tau[i] - p.curve_half[i]; }));
  panel.layers.push_back(points("fitted #gt", kBlack, 1.1, 1, x, fitted, kmNm,
                                [&](std::size_t i) { return p.tau[i]; }));
  return panel;
}

// One part of Eq. 6 against its own variable: raw part (the torque less the
// other fitted parts) as a cloud, the fitted part as a line with its bands.
Panel part_panel(const Inputs& in, const std::vector<double>& x, const std::vector<double>& fit,
                 const std::vector<double>& others_a, const std::vector<double>& others_b,
                 const std::string& part, const std::string& xlabel) {
  Panel panel;
  panel.xlabel = xlabel;
  panel.ylabel = part + " (mN·m)";
  const auto cloud = thin(in.n, in.opt.max_points);
  panel.layers.push_back(points("raw " + part, kCloud, 2.2, 0, x, cloud, kmNm, [&](std::size_t i) {
    return in.d.torque[i] - others_a[i] - others_b[i];
  }));

  // Fitted part: a line through the samples sorted by x. Bands: fewer
  // vertices, as PLplot dashes a line piece by piece.
  const auto order = sorted_by(x);
  auto add_line = [&](Layer l, std::size_t vertices, const std::vector<double>& halfs,
                      double sign) {
    for (const std::size_t k : thin(in.n, vertices)) {
      const std::size_t i = order[k];
      l.x.push_back(x[i]);
      l.y.push_back(kmNm * (fit[i] + (halfs.empty() ? 0.0 : sign * halfs[k])));
    }
    panel.layers.push_back(std::move(l));
  };
  const std::size_t band_vertices = std::min<std::size_t>(in.opt.max_points, 600);
  if (in.has_obs) {
    const auto obs = smoothed_along(in.p.observation_half, order);
    add_line(curve("95% observation band", Mark::Dotted, kObs, 1.3, 3), band_vertices, obs, 1.0);
    add_line(curve("", Mark::Dotted, kObs, 1.3, 3), band_vertices, obs, -1.0);
  }
  const auto band = smoothed_along(in.p.curve_half, order);
  add_line(curve("95% band", Mark::Dashed, kBlack, 1.1, 2), band_vertices, band, 1.0);
  add_line(curve("", Mark::Dashed, kBlack, 1.1, 2), band_vertices, band, -1.0);
  add_line(curve("fitted " + part, Mark::Line, kBlack, 1.6, 1),
           std::min<std::size_t>(in.opt.max_points, 4000), {}, 0.0);
  return panel;
}

// The residual raw τ − fitted τ of every sample.
std::vector<double> residuals(const Inputs& in) {
  std::vector<double> r(in.n);
  for (std::size_t i = 0; i < in.n; ++i) r[i] = in.d.torque[i] - in.p.tau[i];
  return r;
}

// The q-quantile of the finite values of v.
double finite_quantile(const std::vector<double>& v, double q) {
  std::vector<double> f;
  f.reserve(v.size());
  for (const double x : v)
    if (std::isfinite(x)) f.push_back(x);
  return model::quantile(std::move(f), q);
}

// A residual panel's y range (presentation units): six robust standard
// deviations of the residual (median absolute deviation) and the bands'
// usual width, so the transients the fit left out (stick-band samples,
// breakaway) do not shrink the bands to a line. The heading counts what lies
// beyond.
void fit_residual_range(Panel& panel, const Inputs& in, const std::vector<double>& r) {
  std::vector<double> dev(r.size());
  const double med = finite_quantile(r, 0.5);
  for (std::size_t i = 0; i < r.size(); ++i) dev[i] = std::abs(r[i] - med);
  double limit = 6.0 * 1.4826 * finite_quantile(dev, 0.5);
  for (const auto* half : {&in.p.curve_half, &in.p.observation_half}) {
    if (half->empty()) continue;
    const double h = finite_quantile(*half, 0.95);
    if (std::isfinite(h)) limit = std::max(limit, 1.3 * h);
  }
  if (!(limit > 0.0) || !std::isfinite(limit)) return;
  panel.y_limit = kmNm * limit;
  std::size_t beyond = 0;
  for (const double v : r) beyond += std::abs(v) > limit ? 1 : 0;
  if (beyond > 0) {
    panel.heading += " (" + std::to_string(beyond) + " beyond ±" + fmt("%.3g", kmNm * limit) +
                     " mN·m)";
  }
}

Layer band_fill(std::string label, PLINT color, int rank) {
  Layer l = curve(std::move(label), Mark::Fill, color, 1.0, rank);
  return l;
}

// Residual against θ or θ̇ with the shaded bands about zero (bands averaged
// along the axis, as in the part panels).
Panel residual_panel(const Inputs& in, const std::vector<double>& x, const std::string& xlabel) {
  Panel panel;
  panel.heading = "Residual raw #gt − fitted #gt, 95% bands shaded";
  panel.xlabel = xlabel;
  panel.ylabel = "residual (mN·m)";
  const std::vector<double> r = residuals(in);
  const auto order = sorted_by(x);
  const auto vertices = thin(in.n, std::min<std::size_t>(in.opt.max_points, 600));
  auto fill = [&](std::string label, PLINT color, int rank, const std::vector<double>& half) {
    Layer l = band_fill(std::move(label), color, rank);
    const auto smooth = smoothed_along(half, order);
    for (const std::size_t k : vertices) {
      l.x.push_back(x[order[k]]);
      l.y.push_back(kmNm * smooth[k]);
      l.y_low.push_back(-kmNm * smooth[k]);
    }
    return l;
  };
  if (in.has_obs) panel.layers.push_back(fill("95% observation band", kObsFill, 3, in.p.observation_half));
  panel.layers.push_back(points("residual", kCloud, 2.2, 0, x, thin(in.n, in.opt.max_points), kmNm,
                                [&](std::size_t i) { return r[i]; }));
  panel.layers.push_back(fill("95% band of the fit", kCurveFill, 2, in.p.curve_half));
  Layer zero = curve("", Mark::Line, kBlack, 1.0, 1);
  zero.x = {x[order.front()], x[order.back()]};
  zero.y = {0.0, 0.0};
  panel.layers.push_back(std::move(zero));
  fit_residual_range(panel, in, r);
  return panel;
}

std::string with_title(const ReportOptions& opt, const std::string& what) {
  return opt.title.empty() ? what : plplot_escape(opt.title) + " — " + what;
}

std::string summary(const FitResult& r, std::size_t n) {
  std::string s = std::string(model_name(r.model)) + " fit, " + std::to_string(n) + " samples";
  if (r.rmse_Nm > 0.0) s += ", RMSE " + fmt("%.3g", r.rmse_Nm * kmNm) + " mN·m";
  if (r.fit_percent != 0.0) s += ", fit " + fmt("%.1f", r.fit_percent) + "%";
  s += r.detents ? ", detents" : ", no detents";
  return s;
}

Page position_page(const Inputs& in) {
  Page page;
  page.title = with_title(in.opt, "torque vs position");
  page.subtitle = summary(in.r, in.n);
  const std::string xl = "position #gh (rad)";
  page.panels.push_back(total_panel(in, in.d.theta, xl));
  Panel part = part_panel(in, in.d.theta, in.p.pos, in.p.acc, in.p.vel, "#gt#dpos#u", xl);
  part.heading = in.r.detents
                     ? "Position part: #gt#dpos#u = #gt − #gt#dacc#u − #gt#dvel#u"
                     : "Position part: #gt#dpos#u = #gt − #gt#dacc#u − #gt#dvel#u (no detents "
                       "fitted: fitted #gt#dpos#u = 0)";
  page.panels.push_back(std::move(part));
  page.panels.push_back(residual_panel(in, in.d.theta, xl));
  return page;
}

Page velocity_page(const Inputs& in) {
  Page page;
  page.title = with_title(in.opt, "torque vs velocity");
  page.subtitle = summary(in.r, in.n);
  const std::string xl = "velocity #gh\u0307 (rad/s)";
  page.panels.push_back(total_panel(in, in.d.omega, xl));
  Panel part = part_panel(in, in.d.omega, in.p.vel, in.p.acc, in.p.pos, "#gt#dvel#u", xl);
  part.heading = "Velocity part: #gt#dvel#u = #gt − #gt#dacc#u − #gt#dpos#u";
  if (in.r.stick && in.r.stick->dv > 0.0) {
    for (Panel* pn : {&page.panels.front(), &part}) {
      pn->vlines = {-in.r.stick->dv, in.r.stick->dv};
      pn->vline_label = "stick band ±#gDv";
    }
  }
  page.panels.push_back(std::move(part));
  page.panels.push_back(residual_panel(in, in.d.omega, xl));
  return page;
}

Page time_page(const Inputs& in) {
  Page page;
  page.title = with_title(in.opt, "torque vs time");
  page.subtitle = summary(in.r, in.n);
  const auto& d = in.d;
  const auto& p = in.p;
  const auto cloud = thin(in.n, in.opt.max_points);
  const std::size_t line_buckets = std::max<std::size_t>(1, in.opt.max_points / 2);
  const std::size_t band_buckets = std::min<std::size_t>(in.opt.max_points, 1000);
  Panel top, bottom;
  // Shaded ±h(t), h's largest value over each bucket.
  auto band = [&](const char* label, PLINT color, int rank, const std::vector<double>& half) {
    Layer l = band_fill(label, color, rank);
    envelope_series(l, d.t, band_buckets, kmNm, [&](std::size_t i) { return half[i]; });
    for (const double y : l.y) l.y_low.push_back(-y);
    bottom.layers.push_back(std::move(l));
  };

  top.heading = "Raw and fitted torque";
  top.xlabel = "time (s)";
  top.ylabel = "#gt (mN·m)";
  top.layers.push_back(points("raw #gt", kCloud, 2.2, 0, d.t, cloud, kmNm,
                              [&](std::size_t i) { return d.torque[i]; }));
  Layer fitted = curve("fitted #gt", Mark::Line, kBlack, 1.3, 1);
  minmax_series(fitted, d.t, line_buckets, kmNm, [&](std::size_t i) { return p.tau[i]; });
  top.layers.push_back(std::move(fitted));

  bottom.heading = "Residual raw #gt − fitted #gt, 95% bands shaded";
  bottom.xlabel = "time (s)";
  bottom.ylabel = "residual (mN·m)";
  const std::vector<double> r = residuals(in);
  if (in.has_obs) band("95% observation band", kObsFill, 3, p.observation_half);
  bottom.layers.push_back(points("residual", kCloud, 2.2, 0, d.t, cloud, kmNm,
                                 [&](std::size_t i) { return r[i]; }));
  band("95% band of the fit", kCurveFill, 2, p.curve_half);
  Layer zero = curve("", Mark::Line, kBlack, 1.0, 1);
  zero.x = {d.t.front(), d.t.back()};
  zero.y = {0.0, 0.0};
  bottom.layers.push_back(std::move(zero));
  fit_residual_range(bottom, in, r);

  page.panels.push_back(std::move(top));
  page.panels.push_back(std::move(bottom));
  return page;
}

Page ci_page(const Inputs& in) {
  Page page;
  page.title = with_title(in.opt, "95% confidence band of the fitted torque");
  page.subtitle = summary(in.r, in.n);
  Panel panel;
  panel.heading = "Half-width of the fitted curve's 95% band against fitted torque";
  panel.xlabel = "fitted #gt (mN·m)";
  panel.ylabel = "95% band half-width (mN·m)";
  panel.y_from_zero = true;
  const auto idx = thin(in.n, in.opt.max_points);
  Layer pts;
  pts.label = "per sample";
  pts.mark = Mark::Dots;
  pts.color = kBlack;
  pts.size = 1.6;
  for (const std::size_t i : idx) {
    pts.x.push_back(kmNm * in.p.tau[i]);
    pts.y.push_back(kmNm * in.p.curve_half[i]);
  }
  double sum = 0.0;
  std::size_t finite = 0;
  for (const double h : in.p.curve_half) {
    if (!std::isfinite(h)) continue;
    sum += h;
    ++finite;
  }
  Range xr;
  for (const double v : pts.x) xr.add(v);
  panel.layers.push_back(std::move(pts));
  if (finite > 0 && xr.lo <= xr.hi) {
    const double mean = sum / static_cast<double>(finite);
    Layer avg = curve("mean " + fmt("%.3g", mean * kmNm) + " mN·m", Mark::Dashed, kBlack, 1.2, 1);
    avg.x = {xr.lo, xr.hi};
    avg.y = {kmNm * mean, kmNm * mean};
    panel.layers.push_back(std::move(avg));
  }
  page.panels.push_back(std::move(panel));
  return page;
}

void check_inputs(const FitData& data, const Prediction& p, const ReportOptions& opt) {
  const std::size_t n = data.size();
  auto need = [&](std::size_t size, const char* what) {
    if (size != n)
      throw std::invalid_argument(std::string("knoblab::fit::write_report: ") + what + " has " +
                                  std::to_string(size) + " values, the data " +
                                  std::to_string(n));
  };
  if (n == 0) throw std::invalid_argument("knoblab::fit::write_report: no samples");
  need(data.theta.size(), "data.theta");
  need(data.omega.size(), "data.omega");
  need(data.alpha.size(), "data.alpha");
  need(data.torque.size(), "data.torque");
  need(p.tau.size(), "prediction.tau");
  need(p.acc.size(), "prediction.acc");
  need(p.vel.size(), "prediction.vel");
  need(p.pos.size(), "prediction.pos");
  need(p.curve_half.size(), "prediction.curve_half");
  if (!p.observation_half.empty()) need(p.observation_half.size(), "prediction.observation_half");
  if (opt.width_px < 200 || opt.height_px < 200 || opt.width_px > 16384 || opt.height_px > 16384)
    throw std::invalid_argument("knoblab::fit::write_report: image size " +
                                std::to_string(opt.width_px) + "×" +
                                std::to_string(opt.height_px) + " px outside 200…16384");
  if (opt.max_points == 0)
    throw std::invalid_argument("knoblab::fit::write_report: max_points must be positive");
}

}  // namespace

std::vector<fs::path> write_report(const FitResult& r, const FitData& data, const Prediction& p,
                                   const fs::path& dir, const ReportOptions& opt) {
  check_inputs(data, p, opt);

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw std::runtime_error("knoblab::fit::write_report: cannot create directory " +
                             dir.string() + ": " +
                             (ec ? ec.message() : std::string("not a directory")));
  }

  const Inputs in{r, data, p, opt, data.size(), !p.observation_half.empty()};
  const std::pair<const char*, Page> pages[] = {
      {"torque_position", position_page(in)},
      {"torque_velocity", velocity_page(in)},
      {"torque_time", time_page(in)},
      {"ci_torque", ci_page(in)},
  };

  std::vector<fs::path> written;
  const std::lock_guard<std::mutex> lock(plplot_mutex());
  const std::size_t files = 2 * std::size(pages);
  for (const auto& [stem, page] : pages) {
    for (const bool svg : {false, true}) {
      opt.hooks.report("drawing the report", written.size(), files);
      opt.hooks.check();
      const fs::path file = dir / (std::string(stem) + (svg ? ".svg" : ".png"));
      write_plot_file(file, svg, [&](const fs::path& tmp) {
        render(page, tmp, svg ? "svgcairo" : "pngcairo", svg, opt);
      });
      written.push_back(file);
    }
  }
  return written;
}

}  // namespace knoblab::fit
