#include "knoblab/fit/plot/figure_files.hpp"

#include <mutex>
#include <stdexcept>
#include <system_error>

#include "knoblab/fit/plot/figure_csv.hpp"
#include "knoblab/fit/plot/layout.hpp"
#include "knoblab/interchange/atomic_file.hpp"
#include "plot_file.hpp"
#include "render.hpp"
#include "svg_text.hpp"

namespace knoblab::fit::plot {

namespace fs = std::filesystem;

std::vector<fs::path> write_figure(const Figure& fig, const fs::path& dir, const std::string& stem,
                                   const FigureOptions& opt) {
  validate(opt);
  const Layout layout = layout_figure(fig, opt.width_mm, opt.height_mm);
  if (pixels(layout.height_mm, opt.dpi) > kMaxPixels)  // a text page as tall as its text
    throw std::invalid_argument("figure " + stem + " would be " + std::to_string(pixels(layout.height_mm, opt.dpi)) +
                                " px tall, over the PNG limit of " + std::to_string(kMaxPixels) +
                                " px: lower --dpi or give --size a height");
  std::vector<fs::path> written;
  {
    const std::lock_guard<std::mutex> lock(detail::plplot_mutex());
    detail::require_drivers(opt.formats);
    for (const Format format : opt.formats) {
      const fs::path file = dir / (stem + "." + std::string(extension(format)));
      detail::write_plot_file(file, format, [&](const fs::path& tmp) {
        detail::render(fig, layout, format, opt.dpi, tmp);
        if (format == Format::Svg)
          detail::write_bytes(tmp, detail::with_text(detail::read_bytes(tmp), layout,
                                                     detail::device_size(layout, format, opt.dpi)));
        if (format == Format::Png) detail::write_bytes(tmp, detail::with_dpi(detail::read_bytes(tmp), opt.dpi));
      });
      written.push_back(file);
    }
  }
  const fs::path csv = dir / (stem + ".csv");
  try {
    interchange::write_file_atomically(csv, figure_csv(fig));
  } catch (const std::system_error& e) {
    throw std::runtime_error(e.what());
  }
  written.push_back(csv);
  return written;
}

void require_formats(const std::vector<Format>& formats) {
  const std::lock_guard<std::mutex> lock(detail::plplot_mutex());
  detail::require_drivers(formats);
}

std::vector<fs::path> write_figures(const std::vector<NamedFigure>& figures, const fs::path& dir,
                                    const FigureOptions& opt, const BeforeFigure& before_each) {
  validate(opt);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw std::runtime_error("cannot create directory " + dir.string() + ": " +
                             (ec ? ec.message() : std::string("not a directory")));
  std::vector<fs::path> written;
  for (const NamedFigure& f : figures) {
    if (before_each) before_each(static_cast<std::size_t>(&f - figures.data()), figures.size());
    const auto files = write_figure(f.figure, dir, f.stem, opt);
    written.insert(written.end(), files.begin(), files.end());
  }
  return written;
}

}  // namespace knoblab::fit::plot
