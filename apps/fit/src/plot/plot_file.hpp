// One figure file, replaced whole or not at all, and the touches PLplot's
// cairo drivers leave out: a PNG's resolution (pHYs, so a word processor or
// LaTeX places it at its printed size). Internal to the plot module.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "knoblab/fit/plot/figure_options.hpp"

namespace knoblab::fit::plot::detail {

// `draw` writes the temporary path it is given, which becomes `file` only
// once it holds a whole file of its format (a PDF up to %%EOF, an SVG up to
// </svg>, a PNG up to its IEND chunk): the cairo driver reports no write
// errors, so a full disk would otherwise leave half a figure in place of the
// last good one. Throws std::runtime_error naming the file.
void write_plot_file(const std::filesystem::path& file, Format format,
                     const std::function<void(const std::filesystem::path& temporary)>& draw);

// The whole file as bytes; writes bytes over a file. Throw std::runtime_error.
std::string read_bytes(const std::filesystem::path& file);
void write_bytes(const std::filesystem::path& file, const std::string& bytes);

// `png` with a pHYs chunk after its IHDR saying `dpi` (replacing one it has).
// Throws std::runtime_error when `png` does not begin as a PNG does.
std::string with_dpi(std::string png, int dpi);

}  // namespace knoblab::fit::plot::detail
