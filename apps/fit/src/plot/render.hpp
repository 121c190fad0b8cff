// Drawing a laid-out figure with PLplot's cairo drivers (pdfcairo,
// svgcairo, pngcairo), one PLplot stream per file. Internal to the plot
// module: write_figure (figure_files.hpp) is the way in.
#pragma once

#include <filesystem>
#include <mutex>
#include <vector>

#include "knoblab/fit/plot/figure.hpp"
#include "knoblab/fit/plot/figure_options.hpp"
#include "knoblab/fit/plot/layout.hpp"

namespace knoblab::fit::plot::detail {

// PLplot keeps global state: held around every render in the process.
std::mutex& plplot_mutex();

// The page in the device's units: points for PDF; pixels at `dpi` for PNG
// and for SVG (whose point clouds are one embedded image, at that
// resolution; svg_text.hpp gives the SVG its size in mm).
struct DeviceSize {
  int width = 0, height = 0;
};
DeviceSize device_size(const Layout& layout, Format format, int dpi);

// Throws std::runtime_error when this PLplot lacks the cairo driver of one of
// `formats` (a build with only some of them): asked for a driver it does not
// have, PLplot would prompt on stdin for another. The caller holds
// plplot_mutex().
void require_drivers(const std::vector<Format>& formats);

// Draws `fig` as `layout` places it into `file`. PDF and PNG get their text
// from PLplot; an SVG's text is left to svg_text.hpp, as <text> elements.
// Throws std::runtime_error naming `file` when it cannot be opened.
// The caller holds plplot_mutex().
void render(const Figure& fig, const Layout& layout, Format format, int dpi,
            const std::filesystem::path& file);

}  // namespace knoblab::fit::plot::detail
