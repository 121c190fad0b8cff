#include "svg_text.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "knoblab/fit/plot/text.hpp"

namespace knoblab::fit::plot::detail {

namespace {

// How far a subscript sinks and a superscript rises, in ems of the base size
// (as PLplot's cairo driver places them).
constexpr double kSubDrop = 0.3, kSupRise = 0.45;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string xml(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Sets attribute `name` of the tag spanning [begin, end) of `s`; returns the
// tag's new end.
std::size_t set_attribute(std::string& s, std::size_t begin, std::size_t end, const std::string& name,
                          const std::string& value) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = s.find(key, begin);
  if (at == std::string::npos || at >= end) {
    s.insert(end, key + value + "\"");
    return end + key.size() + value.size() + 1;
  }
  const std::size_t v0 = at + key.size(), v1 = s.find('"', v0);
  s.replace(v0, v1 - v0, value);
  return end + value.size() - (v1 - v0);
}

std::string text_element(const TextItem& t, double sx, double sy, double H) {
  const double x = t.x * sx, y = (H - t.y) * sy;
  const double size = t.size_pt * kPtMm * sx;
  std::string e = "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) + "\"";
  if (t.anchor != Anchor::Start) e += t.anchor == Anchor::Middle ? " text-anchor=\"middle\"" : " text-anchor=\"end\"";
  if (t.vertical) e += " transform=\"rotate(-90 " + num(x) + " " + num(y) + ")\"";
  e += ">";
  double shift = 0.0;  // the baseline's offset so far, down positive
  for (const Run& r : runs(t.text)) {
    if (r.level == 0 && shift == 0.0) {
      e += xml(r.text);
      continue;
    }
    const double target = r.level < 0 ? kSubDrop * size * -r.level : -kSupRise * size * r.level;
    e += "<tspan dy=\"" + num(target - shift) + "\"";
    if (r.level != 0) e += " font-size=\"" + num(size * std::pow(kScriptScale, std::abs(r.level))) + "\"";
    e += ">" + xml(r.text) + "</tspan>";
    shift = target;
  }
  return e + "</text>\n";
}

}  // namespace

std::string with_text(std::string svg, const Layout& layout, DeviceSize size) {
  const std::size_t root = svg.find("<svg");
  const std::size_t root_end = root == std::string::npos ? root : svg.find('>', root);
  const std::size_t close = svg.rfind("</svg>");
  if (root_end == std::string::npos || close == std::string::npos || close < root_end)
    throw std::runtime_error("the SVG came out without its root element");
  std::size_t end = set_attribute(svg, root, root_end, "width", num(layout.width_mm) + "mm");
  end = set_attribute(svg, root, end, "height", num(layout.height_mm) + "mm");
  set_attribute(svg, root, end, "viewBox", "0 0 " + std::to_string(size.width) + " " + std::to_string(size.height));

  const double sx = size.width / layout.width_mm, sy = size.height / layout.height_mm;
  // Spaces kept as written: the one after a subscript is in a tspan of its own.
  std::string text =
      "<g font-family=\"DejaVu Sans, Bitstream Vera Sans, Verdana, Arial, sans-serif\" fill=\"#000000\" "
      "xml:space=\"preserve\" style=\"white-space: pre\">\n";
  for (const TextItem& t : layout.texts) text += text_element(t, sx, sy, layout.height_mm);
  text += "</g>\n";
  svg.insert(svg.rfind("</svg>"), text);
  return svg;
}

}  // namespace knoblab::fit::plot::detail
