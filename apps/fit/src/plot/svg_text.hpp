// An SVG's text as text: cairo writes glyphs as outlines, so the SVG is drawn
// without text and the layout's text is added as <text> elements (real text
// an editor can change and a search can find), and the page gets its printed
// size in mm. Internal to the plot module.
#pragma once

#include <string>

#include "knoblab/fit/plot/layout.hpp"
#include "render.hpp"

namespace knoblab::fit::plot::detail {

// `svg` (cairo's, drawn at `size`) with its root's width and height in mm
// and the layout's texts before its closing tag. Throws std::runtime_error
// when `svg` has no root element or no end.
std::string with_text(std::string svg, const Layout& layout, DeviceSize size);

}  // namespace knoblab::fit::plot::detail
