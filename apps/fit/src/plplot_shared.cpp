#include "knoblab/fit/plplot_shared.hpp"

#include <plplot.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include "knoblab/interchange/atomic_file.hpp"

namespace knoblab::fit {

std::mutex& plplot_mutex() {
  static std::mutex m;
  return m;
}

namespace {

// The tail a whole file of its kind ends with: PNG's IEND chunk (its type
// and CRC, the last 8 bytes), the SVG root's closing tag.
bool ends_whole(const std::filesystem::path& path, bool svg) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 64);
  if (!in || size <= 0) return false;
  in.seekg(size - tail);
  std::string end(static_cast<std::size_t>(tail), '\0');
  in.read(end.data(), tail);
  if (!in) return false;
  if (svg) return end.find("</svg>") != std::string::npos;
  return end.size() >= 12 && end.compare(end.size() - 8, 4, "IEND") == 0;
}

}  // namespace

void write_plot_file(const std::filesystem::path& file, bool svg,
                     const std::function<void(const std::filesystem::path& temporary)>& draw) {
  try {
    interchange::PendingFile pending(file);
    draw(pending.temporary());
    if (!ends_whole(pending.temporary(), svg))
      throw std::runtime_error("cannot write " + file.string() + ": the plot came out incomplete (disk full?)");
    pending.commit();
  } catch (const std::system_error& e) {
    throw std::runtime_error(e.what());
  }
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
