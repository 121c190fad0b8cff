// PLplot drawing of a laid-out figure. World coordinates are the layout's mm
// for everything on the page (frames, ticks, text, legends) and each panel's
// data window inside its box; PLplot clips the data to the box. Sizes in mm
// become device units through the page's own scale, so a figure looks the
// same at any dpi.
#include "render.hpp"

#include <plplot.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/fit/plot/text.hpp"

namespace knoblab::fit::plot::detail {

namespace {

namespace fs = std::filesystem;

constexpr PLINT kInk = 15;  // the cmap0 entry every colour is set into

struct Device {
  double units_per_mm = 1.0;     // line widths: device units (px, pt) a mm
  double plplot_mm_per_mm = 1.0; // PLplot's page mm (72 a device inch) a printed mm
  double default_char = 1.0;     // PLplot's default character height, its mm
  double W = 1.0, H = 1.0;       // the page in printed mm
  bool raster_dots = false;      // SVG: each run of dots one embedded image
};

void ink(const Rgb& c) {
  plscol0a(kInk, c.r, c.g, c.b, c.alpha);
  plcol0(kInk);
}

// Dash patterns in printed mm (PLplot takes micrometres of its page mm).
void line_style(Mark m, const Device& d) {
  const auto um = [&](double mm) { return static_cast<PLINT>(std::lround(mm * d.plplot_mm_per_mm * 1000.0)); };
  if (m == Mark::Dashed || m == Mark::VLines) {
    const PLINT mark[1] = {um(2.2)}, space[1] = {um(1.2)};
    plstyl(1, mark, space);
  } else if (m == Mark::Dotted) {
    const PLINT mark[1] = {um(0.5)}, space[1] = {um(0.9)};
    plstyl(1, mark, space);
  } else {
    plstyl(0, nullptr, nullptr);
  }
}

void page_window(const Device& d) {
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, d.W, 0.0, d.H);
}

// Runs of finite points, each handed to `draw`.
template <typename Draw>
void finite_runs(const Series& s, bool with_low, Draw draw) {
  std::vector<PLFLT> x, y, lo;
  const auto flush = [&] {
    if (!x.empty()) draw(x, y, lo);
    x.clear(), y.clear(), lo.clear();
  };
  for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
    const bool ok = std::isfinite(s.x[i]) && std::isfinite(s.y[i]) &&
                    (!with_low || (i < s.y_low.size() && std::isfinite(s.y_low[i])));
    if (!ok) {
      flush();
      continue;
    }
    x.push_back(s.x[i]);
    y.push_back(s.y[i]);
    if (with_low) lo.push_back(s.y_low[i]);
  }
  flush();
}

void dots(std::vector<PLFLT>& x, std::vector<PLFLT>& y) {
  // A zero-length line with the cairo driver's round caps: a dot as wide as the pen.
  plpoin(static_cast<PLINT>(x.size()), x.data(), y.data(), -1);
}

void draw_series(const Series& s, const PanelLayout& pl, const Device& d) {
  if (s.x.empty()) return;
  ink(s.color);
  plwidth(s.size_mm * d.units_per_mm);
  switch (s.mark) {
    case Mark::Dots:
      if (d.raster_dots) pl_cmd(PLESC_START_RASTERIZE, nullptr);
      finite_runs(s, false, [](auto& x, auto& y, auto&) { dots(x, y); });
      if (d.raster_dots) pl_cmd(PLESC_END_RASTERIZE, nullptr);
      break;
    case Mark::Line:
    case Mark::Dashed:
    case Mark::Dotted:
      line_style(s.mark, d);
      finite_runs(s, false, [](auto& x, auto& y, auto&) {
        if (x.size() > 1) plline(static_cast<PLINT>(x.size()), x.data(), y.data());
      });
      line_style(Mark::Line, d);
      break;
    case Mark::Fill:
      plwidth(0.0);  // the cairo driver strokes a fill's outline too
      finite_runs(s, true, [](auto& x, auto& y, auto& lo) {
        if (x.size() < 2) return;
        for (std::size_t i = lo.size(); i-- > 0;) x.push_back(x[i]), y.push_back(lo[i]);
        plfill(static_cast<PLINT>(x.size()), x.data(), y.data());
      });
      break;
    case Mark::Stems:
      finite_runs(s, false, [&](auto& x, auto& y, auto&) {
        for (std::size_t i = 0; i < x.size(); ++i) pljoin(x[i], 0.0, x[i], y[i]);
        plwidth(2.5 * s.size_mm * d.units_per_mm);
        dots(x, y);
        plwidth(s.size_mm * d.units_per_mm);
      });
      break;
    case Mark::VLines:
      line_style(s.mark, d);
      for (const double x : s.x)
        if (std::isfinite(x)) pljoin(x, pl.y_lo, x, pl.y_hi);
      line_style(Mark::Line, d);
      break;
  }
}

void draw_legend_sample(const LegendSample& ls, const Device& d) {
  const Box& b = ls.box;
  const LegendEntry& e = ls.entry;
  const double cy = (b.y0 + b.y1) / 2;
  ink(e.color);
  switch (e.mark) {
    case Mark::Dots:
    case Mark::Stems: {
      // Bigger than a cloud's dots, as matplotlib's markerscale: seen at all.
      plwidth(std::max(1.4, 2.5 * e.size_mm) * d.units_per_mm);
      PLFLT x[1] = {(b.x0 + b.x1) / 2}, y[1] = {cy};
      plpoin(1, x, y, -1);
      break;
    }
    case Mark::Line:
    case Mark::Dashed:
    case Mark::Dotted:
    case Mark::VLines:
      plwidth(e.size_mm * d.units_per_mm);
      line_style(e.mark, d);
      pljoin(b.x0, cy, b.x1, cy);
      line_style(Mark::Line, d);
      break;
    case Mark::Fill: {
      plwidth(0.0);
      PLFLT x[4] = {b.x0, b.x1, b.x1, b.x0}, y[4] = {b.y0, b.y0, b.y1, b.y1};
      plfill(4, x, y);
      break;
    }
  }
}

// PLplot puts plptex's reference point at the middle of the capitals' height.
void draw_text(const TextItem& t, const Device& d) {
  const double cap_mm = kCapHeightEm * t.size_pt * kPtMm;
  plschr(0.0, cap_mm * d.plplot_mm_per_mm / d.default_char);
  const double just = t.anchor == Anchor::Start ? 0.0 : t.anchor == Anchor::Middle ? 0.5 : 1.0;
  if (t.vertical) plptex(t.x - cap_mm / 2, t.y, 0.0, 1.0, just, t.text.c_str());
  else plptex(t.x, t.y + cap_mm / 2, 1.0, 0.0, just, t.text.c_str());
}

const char* device_name(Format f) {
  switch (f) {
    case Format::Pdf: return "pdfcairo";
    case Format::Svg: return "svgcairo";
    case Format::Png: return "pngcairo";
  }
  return "";
}

}  // namespace

std::mutex& plplot_mutex() {
  static std::mutex m;
  return m;
}

DeviceSize device_size(const Layout& layout, Format format, int dpi) {
  if (format == Format::Pdf)
    return {static_cast<int>(std::lround(layout.width_mm / kPtMm)),
            static_cast<int>(std::lround(layout.height_mm / kPtMm))};
  return {pixels(layout.width_mm, dpi), pixels(layout.height_mm, dpi)};
}

void require_drivers(const std::vector<Format>& formats) {
  constexpr int kMostDevices = 128;
  PLCHAR_VECTOR menu[kMostDevices], names[kMostDevices];
  PLCHAR_VECTOR *menu_p = menu, *names_p = names;  // PLplot fills the arrays these point at
  int count = kMostDevices;
  plgDevs(&menu_p, &names_p, &count);
  std::string have;
  for (int k = 0; k < count; ++k)
    if (std::strstr(names[k], "cairo") != nullptr) have += (have.empty() ? "" : ", ") + std::string(names[k]);
  for (const Format f : formats) {
    bool found = false;
    for (int k = 0; k < count; ++k) found = found || std::strcmp(names[k], device_name(f)) == 0;
    if (!found)
      throw std::runtime_error("this PLplot has no " + std::string(device_name(f)) + " driver (its cairo drivers: " +
                               (have.empty() ? "none" : have) + "): leave " + std::string(extension(f)) +
                               " out of --format");
  }
}

void render(const Figure& fig, const Layout& layout, Format format, int dpi, const fs::path& file) {
  // Opened here: PLplot would prompt on stdin and exit() on a path it cannot
  // open. The driver closes it at plend1.
  std::FILE* fp = std::fopen(file.c_str(), "wb");
  if (fp == nullptr) throw std::runtime_error("cannot write " + file.string() + ": " + std::strerror(errno));
  PLINT previous = 0, stream = -1;
  plgstrm(&previous);
  plmkstrm(&stream);
  if (stream < 0) {
    std::fclose(fp);
    throw std::runtime_error("cannot write " + file.string() + ": no free PLplot stream");
  }
  struct EndStream {
    PLINT previous;
    ~EndStream() {
      plend1();  // also frees the stream
      plsstrm(previous);
    }
  } end{previous};

  const DeviceSize size = device_size(layout, format, dpi);
  plsdev(device_name(format));
  plsfile(fp);
  plspage(0.0, 0.0, size.width, size.height, 0, 0);
  plscmap0n(kInk + 1);
  plscolbg(255, 255, 255);
  plinit();
  pladv(0);

  Device d;
  d.W = layout.width_mm;
  d.H = layout.height_mm;
  d.units_per_mm = size.width / layout.width_mm;
  PLFLT x0, x1, y0, y1;
  plgspa(&x0, &x1, &y0, &y1);
  d.plplot_mm_per_mm = (x1 - x0) / layout.width_mm;
  PLFLT def = 0.0, ht = 0.0;
  plgchr(&def, &ht);
  d.default_char = def;
  d.raster_dots = format == Format::Svg;

  for (std::size_t i = 0; i < layout.panels.size() && i < fig.panels.size(); ++i) {
    const PanelLayout& pl = layout.panels[i];
    plvpor(pl.box.x0 / d.W, pl.box.x1 / d.W, pl.box.y0 / d.H, pl.box.y1 / d.H);
    plwind(pl.x_lo, pl.x_hi, pl.y_lo, pl.y_hi);
    for (const Series& s : fig.panels[i].series) draw_series(s, pl, d);
  }
  page_window(d);
  for (const PanelLayout& pl : layout.panels)
    for (const LegendSample& ls : pl.legend) draw_legend_sample(ls, d);
  ink(palette::kBlack);
  for (const Segment& s : layout.rules) {
    plwidth(s.width_mm * d.units_per_mm);
    pljoin(s.x0, s.y0, s.x1, s.y1);
  }
  if (format != Format::Svg)
    for (const TextItem& t : layout.texts) draw_text(t, d);
}

}  // namespace knoblab::fit::plot::detail
