// What tests check of a figure file: a PNG's IHDR size and pHYs resolution,
// a PDF's structure and the text drawing operators in its (deflated) content
// streams, an SVG parsed as XML with the text of its <text> elements, a CSV
// split into rows and fields.
#pragma once

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace knoblab::testing {

inline std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

struct PngInfo {
  std::uint32_t width = 0, height = 0;
  std::optional<double> dpi;  // from pHYs, when it says metres
};

// Throws std::runtime_error for something that is not a PNG.
inline PngInfo png_info(const std::string& png) {
  if (png.size() < 33 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || png.compare(12, 4, "IHDR") != 0)
    throw std::runtime_error("not a PNG");
  PngInfo info{be32(png, 16), be32(png, 20), std::nullopt};
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t len = be32(png, at);
    if (png.compare(at + 4, 4, "pHYs") == 0 && len == 9 && png[at + 16] == 1)
      info.dpi = be32(png, at + 8) * 0.0254;
    at += 12 + len;
  }
  return info;
}

// Every "stream … endstream" of a PDF, inflated where it is FlateDecode'd
// (cairo's content streams are), as written otherwise.
inline std::vector<std::string> pdf_streams(const std::string& pdf) {
  std::vector<std::string> out;
  for (std::size_t at = pdf.find("stream"); at != std::string::npos; at = pdf.find("stream", at)) {
    if (at >= 3 && pdf.compare(at - 3, 3, "end") == 0) {
      at += 6;
      continue;
    }
    std::size_t begin = at + 6;
    if (pdf.compare(begin, 2, "\r\n") == 0) begin += 2;
    else if (pdf[begin] == '\n') begin += 1;
    const std::size_t end = pdf.find("endstream", begin);
    if (end == std::string::npos) break;
    const std::string raw = pdf.substr(begin, end - begin);
    std::string inflated(raw.size() * 20 + 4096, '\0');
    uLongf len = static_cast<uLongf>(inflated.size());
    if (uncompress(reinterpret_cast<Bytef*>(inflated.data()), &len, reinterpret_cast<const Bytef*>(raw.data()),
                   static_cast<uLong>(raw.size())) == Z_OK)
      out.push_back(inflated.substr(0, len));
    else
      out.push_back(raw);
    at = end + 9;
  }
  return out;
}

// Whether `needle` is in the PDF, as written or in an inflated stream (cairo
// keeps the page dictionaries in a compressed object stream).
inline bool pdf_contains(const std::string& pdf, const std::string& needle) {
  if (pdf.find(needle) != std::string::npos) return true;
  for (const std::string& s : pdf_streams(pdf))
    if (s.find(needle) != std::string::npos) return true;
  return false;
}

// The text a PDF shows in its fonts' own encoding: the literal strings of its
// content streams' TJ and Tj operators, joined in order ("(Kn)17(ob)" is
// "Knob"; glyphs outside the font's simple encoding, written as <hex>, are
// left out). Counted: how many such operators there are.
struct PdfText {
  std::string text;
  std::size_t operators = 0;
};
inline PdfText pdf_text(const std::string& pdf) {
  PdfText out;
  for (const std::string& s : pdf_streams(pdf)) {
    for (std::size_t at = 0; at + 1 < s.size(); ++at) {
      if (s.compare(at, 2, "TJ") == 0 || s.compare(at, 2, "Tj") == 0) ++out.operators;
      if (s[at] != '(') continue;
      for (++at; at < s.size() && s[at] != ')'; ++at) {
        if (s[at] != '\\') {
          out.text += s[at];
          continue;
        }
        const char e = s[++at];
        if (e >= '0' && e <= '7') {  // \ddd, octal
          int v = 0;
          for (int k = 0; k < 3 && s[at] >= '0' && s[at] <= '7'; ++k) v = 8 * v + (s[at++] - '0');
          --at;
          out.text += static_cast<char>(v);
        } else {
          out.text += e == 'n' ? '\n' : e;
        }
      }
    }
  }
  return out;
}

// A small XML reader: checks that `xml` is well formed (one root element,
// tags nested and closed, attributes quoted, entities known) and collects
// the text content of every <text> element. Throws std::runtime_error
// saying where it is not.
struct XmlText {
  std::string root;                // the root element's name
  std::map<std::string, std::string> root_attributes;
  std::vector<std::string> texts;  // <text> contents, tspans' text joined
};

inline XmlText parse_svg(const std::string& xml) {
  XmlText out;
  std::vector<std::string> open;
  std::size_t at = 0;
  int in_text = 0;
  std::string text;
  const auto fail = [&](const std::string& why) {
    throw std::runtime_error("not well-formed XML at byte " + std::to_string(at) + ": " + why);
  };
  const auto decode = [&](std::size_t from, std::size_t to) {
    std::string s;
    for (std::size_t i = from; i < to; ++i) {
      if (xml[i] != '&') {
        s += xml[i];
        continue;
      }
      const std::size_t semi = xml.find(';', i);
      if (semi == std::string::npos || semi > to) fail("unterminated entity");
      const std::string e = xml.substr(i + 1, semi - i - 1);
      if (e == "amp") s += '&';
      else if (e == "lt") s += '<';
      else if (e == "gt") s += '>';
      else if (e == "quot") s += '"';
      else if (e == "apos") s += '\'';
      else if (e.size() > 1 && e[0] == '#') {
        const unsigned long c = e[1] == 'x' ? std::stoul(e.substr(2), nullptr, 16) : std::stoul(e.substr(1));
        if (c < 0x80) s += static_cast<char>(c);
        else if (c < 0x800) s += static_cast<char>(0xC0 | (c >> 6)), s += static_cast<char>(0x80 | (c & 0x3F));
        else
          s += static_cast<char>(0xE0 | (c >> 12)), s += static_cast<char>(0x80 | ((c >> 6) & 0x3F)),
              s += static_cast<char>(0x80 | (c & 0x3F));
      } else
        fail("unknown entity &" + e + ";");
      i = semi;
    }
    return s;
  };
  bool had_root = false;
  while (at < xml.size()) {
    const std::size_t lt = xml.find('<', at);
    if (lt == std::string::npos) {
      if (!open.empty()) fail("unclosed <" + open.back() + ">");
      break;
    }
    if (in_text) text += decode(at, lt);
    at = lt;
    if (xml.compare(at, 4, "<!--") == 0) {
      const std::size_t e = xml.find("-->", at);
      if (e == std::string::npos) fail("unterminated comment");
      at = e + 3;
      continue;
    }
    if (xml.compare(at, 2, "<?") == 0 || xml.compare(at, 2, "<!") == 0) {
      const std::size_t e = xml.find('>', at);
      if (e == std::string::npos) fail("unterminated declaration");
      at = e + 1;
      continue;
    }
    const bool closing = xml.compare(at, 2, "</") == 0;
    std::size_t i = at + (closing ? 2 : 1);
    const std::size_t name_end = xml.find_first_of(" \t\r\n/>", i);
    if (name_end == std::string::npos || name_end == i) fail("a tag without a name");
    const std::string name = xml.substr(i, name_end - i);
    i = name_end;
    std::map<std::string, std::string> attributes;
    for (;;) {
      while (i < xml.size() && std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
      if (i >= xml.size()) fail("unterminated tag <" + name + ">");
      if (xml[i] == '>' || xml.compare(i, 2, "/>") == 0) break;
      if (closing) fail("attributes in a closing tag");
      const std::size_t eq = xml.find('=', i);
      if (eq == std::string::npos) fail("an attribute without a value");
      const std::string key = xml.substr(i, eq - i);
      const char q = xml[eq + 1];
      if (q != '"' && q != '\'') fail("attribute " + key + " not quoted");
      const std::size_t close = xml.find(q, eq + 2);
      if (close == std::string::npos) fail("attribute " + key + " not closed");
      if (xml.substr(eq + 2, close - eq - 2).find('<') != std::string::npos) fail("'<' in attribute " + key);
      attributes[key] = decode(eq + 2, close);
      i = close + 1;
    }
    const bool empty = xml[i] == '/';
    at = i + (empty ? 2 : 1);
    if (closing) {
      if (open.empty() || open.back() != name) fail("</" + name + "> closes " + (open.empty() ? "nothing" : "<" + open.back() + ">"));
      open.pop_back();
      if (name == "text" && --in_text == 0) out.texts.push_back(text);
      continue;
    }
    if (open.empty()) {
      if (had_root) fail("a second root element <" + name + ">");
      had_root = true;
      out.root = name;
      out.root_attributes = attributes;
    }
    if (empty) continue;
    open.push_back(name);
    if (name == "text" && in_text++ == 0) text.clear();
  }
  if (!had_root) fail("no root element");
  return out;
}

// A CSV's lines split at commas (fields here are never quoted with commas).
inline std::vector<std::vector<std::string>> csv_rows(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::size_t at = 0;
  while (at < csv.size()) {
    const std::size_t nl = std::min(csv.find('\n', at), csv.size());
    std::vector<std::string> fields;
    std::size_t f = at;
    for (;;) {
      const std::size_t comma = std::min(csv.find(',', f), nl);
      fields.push_back(csv.substr(f, comma - f));
      if (comma >= nl) break;
      f = comma + 1;
    }
    rows.push_back(std::move(fields));
    at = nl + 1;
  }
  return rows;
}

}  // namespace knoblab::testing
