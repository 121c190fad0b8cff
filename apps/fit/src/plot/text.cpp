#include "knoblab/fit/plot/text.hpp"

#include <algorithm>
#include <cmath>

#include "dejavu_widths.hpp"

namespace knoblab::fit::plot {

namespace {

// The next code point of UTF-8 `s` from `at` (advanced past it); a stray
// byte counts as one character.
std::uint32_t next_code(std::string_view s, std::size_t& at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(at);
  std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 1;
  if (at + len > s.size()) len = 1;
  std::uint32_t code = len == 1 ? c : c & (0x7Fu >> len);
  for (std::size_t k = 1; k < len; ++k) code = (code << 6) | (byte(at + k) & 0x3Fu);
  at += len;
  return code;
}

double advance_em(std::uint32_t code) {
  const auto* begin = std::begin(detail::kDejaVuSans);
  const auto* end = std::end(detail::kDejaVuSans);
  const auto* it = std::lower_bound(begin, end, code,
                                    [](const detail::Advance& a, std::uint32_t c) { return a.code < c; });
  if (it != end && it->code == code) return it->width / detail::kUnitsPerEm;
  if (code >= 0x300 && code < 0x370) return 0.0;  // combining marks
  return 0.65;                                     // a typical letter's width
}

}  // namespace

std::string escape(std::string_view plain) {
  std::string out;
  out.reserve(plain.size());
  for (const char c : plain) {
    out += c;
    if (c == '#') out += '#';
  }
  return out;
}

std::vector<Run> runs(std::string_view markup) {
  std::vector<Run> out(1);
  int level = 0;
  for (std::size_t i = 0; i < markup.size(); ++i) {
    const char c = markup[i];
    if (c == '#' && i + 1 < markup.size()) {
      const char e = markup[i + 1];
      if (e == '#') {
        out.back().text += '#';
        ++i;
        continue;
      }
      if (e == 'd' || e == 'u') {
        level += e == 'u' ? 1 : -1;
        if (!out.back().text.empty()) out.emplace_back();
        out.back().level = level;
        ++i;
        continue;
      }
    }
    out.back().text += c;
  }
  if (out.back().text.empty() && out.size() > 1) out.pop_back();
  return out;
}

std::string plain(std::string_view markup) {
  std::string out;
  for (const Run& r : runs(markup)) out += r.text;
  return out;
}

double width_em(std::string_view markup) {
  double w = 0.0;
  for (const Run& r : runs(markup)) {
    double run = 0.0;
    for (std::size_t at = 0; at < r.text.size();) run += advance_em(next_code(r.text, at));
    w += run * std::pow(kScriptScale, std::abs(r.level));
  }
  return w;
}

std::vector<std::string> wrap(std::string_view markup, double width, double size_pt) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t at = 0;
  while (at <= markup.size()) {
    const std::size_t sp = std::min(markup.find(' ', at), markup.size());
    const std::string_view word = markup.substr(at, sp - at);
    at = sp + 1;
    if (word.empty()) continue;
    const std::string longer = line.empty() ? std::string(word) : line + " " + std::string(word);
    if (!line.empty() && width_mm(longer, size_pt) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

FittedText fit_text(std::string_view markup, double width, double size_pt, double min_pt,
                    std::size_t max_lines) {
  const double w1 = width_mm(markup, 1.0);  // mm a point of size
  if (w1 * size_pt <= width) return {{std::string(markup)}, size_pt};
  if (w1 * min_pt <= width) return {{std::string(markup)}, width / w1};
  max_lines = std::max<std::size_t>(1, max_lines);
  double size = min_pt;
  for (;;) {
    std::vector<std::string> lines = wrap(markup, width, size);
    bool fits = lines.size() <= max_lines;
    for (const std::string& l : lines) fits = fits && width_mm(l, size) <= width;
    if (fits || size < 0.5) {
      // Lines of even length rather than a long one and a last word: the
      // narrowest width that still takes no more lines.
      for (double w = 0.98 * width; w > 0.3 * width; w *= 0.98) {
        std::vector<std::string> narrower = wrap(markup, w, size);
        bool ok = narrower.size() == lines.size();
        for (const std::string& l : narrower) ok = ok && width_mm(l, size) <= w;
        if (!ok) break;
        lines = std::move(narrower);
      }
      return {std::move(lines), size};
    }
    size *= 0.95;
  }
}

}  // namespace knoblab::fit::plot
