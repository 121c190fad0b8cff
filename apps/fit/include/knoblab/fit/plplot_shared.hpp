// What every PLplot report in the process shares: PLplot keeps global state,
// so one lock serialises all of them (the fit report and the discrepancy
// report alike), one rule for showing text as written, and one page setup
// (type scale, pen, the title lines).
#pragma once

#include <filesystem>
#include <functional>
#include <mutex>
#include <string>

namespace knoblab::fit {

// Held while a PLplot stream is open, by every report.
std::mutex& plplot_mutex();

// One plot file, replaced whole or not at all: `draw` renders into the
// temporary path it is given, which becomes `file` only once it holds a whole
// PNG (up to its IEND chunk) or SVG (up to </svg>). PLplot's cairo driver
// reports no write errors, so a full disk would otherwise leave half a plot
// in place of the last good one. Throws std::runtime_error naming the file.
void write_plot_file(const std::filesystem::path& file, bool svg,
                     const std::function<void(const std::filesystem::path& temporary)>& draw);

// PLplot's escape character '#' doubled, so text is shown as written.
std::string plplot_escape(const std::string& s);

// A page's size and type scale, measured from the open stream.
struct PageMetrics {
  double char_mm = 0;                   // character height after scaling
  double def_mm = 1;                    // PLplot's default one (plschr scales it)
  double page_w_mm = 0, page_h_mm = 0;
  double pen = 1.0;                     // one pen width in PLplot width units (pixels)
  bool vector = false;                  // SVG: point clouds are embedded as one raster image
};

// Advances to a new page and sets its type: characters 1/50 of the smaller
// page side (the cairo driver's text comes out about a third larger), pens
// one 600th of the smaller pixel side.
PageMetrics begin_page(int width_px, int height_px, bool vector);

// Text centred on the page, `y_chars` character heights below its top edge,
// `scale` times the page's character height.
void page_text(double y_chars, double scale, const PageMetrics& m, const std::string& text);

}  // namespace knoblab::fit
