#include "knoblab/fit/plplot_shared.hpp"

#include <plplot.h>

#include <algorithm>

namespace knoblab::fit {

std::mutex& plplot_mutex() {
  static std::mutex m;
  return m;
}

std::string plplot_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    out += c;
    if (c == '#') out += '#';
  }
  return out;
}

PageMetrics begin_page(int width_px, int height_px, bool vector) {
  pladv(0);
  PageMetrics m;
  m.vector = vector;
  PLFLT x0, x1, y0, y1;
  plgspa(&x0, &x1, &y0, &y1);
  m.page_w_mm = x1 - x0;
  m.page_h_mm = y1 - y0;
  m.char_mm = std::min(m.page_w_mm, m.page_h_mm) / 50.0;
  PLFLT def = 0, ht = 0;
  plgchr(&def, &ht);
  m.def_mm = def;
  plschr(0.0, m.char_mm / m.def_mm);
  m.pen = std::max(1.0, std::min(width_px, height_px) / 600.0);
  return m;
}

void page_text(double y_chars, double scale, const PageMetrics& m, const std::string& text) {
  plschr(0.0, scale * m.char_mm / m.def_mm);
  plmtex("t", -y_chars / scale, 0.5, 0.5, text.c_str());
  plschr(0.0, m.char_mm / m.def_mm);
}

}  // namespace knoblab::fit
