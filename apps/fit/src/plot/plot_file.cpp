#include "plot_file.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include "knoblab/interchange/atomic_file.hpp"

namespace knoblab::fit::plot::detail {

namespace {

// The tail a whole file of its kind ends with.
bool ends_whole(const std::string& bytes, Format format) {
  const std::string tail = bytes.substr(bytes.size() - std::min<std::size_t>(bytes.size(), 64));
  switch (format) {
    case Format::Pdf: return tail.find("%%EOF") != std::string::npos;
    case Format::Svg: return tail.find("</svg>") != std::string::npos;
    case Format::Png:  // IEND's type and CRC are the last 8 bytes
      return tail.size() >= 12 && tail.compare(tail.size() - 8, 4, "IEND") == 0;
  }
  return false;
}

void put32(std::string& s, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) s += static_cast<char>((v >> shift) & 0xFF);
}

std::uint32_t get32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

}  // namespace

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw std::runtime_error("cannot read " + file.string());
  return bytes;
}

void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.flush();
  if (!out) throw std::runtime_error("cannot write " + file.string() + ": the disk may be full");
}

std::string with_dpi(std::string png, int dpi) {
  constexpr std::size_t kAfterIhdr = 8 + 4 + 4 + 13 + 4;  // signature, IHDR's length, type, data, CRC
  if (png.size() < kAfterIhdr || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || png.compare(12, 4, "IHDR") != 0)
    throw std::runtime_error("not a PNG");
  // A pHYs chunk already there (the cairo driver writes none) goes.
  for (std::size_t at = kAfterIhdr; at + 12 <= png.size();) {
    const std::uint32_t len = get32(png, at);
    if (png.compare(at + 4, 4, "pHYs") == 0) {
      png.erase(at, 12 + len);
      break;
    }
    if (png.compare(at + 4, 4, "IDAT") == 0) break;  // pHYs must come before the image data
    at += 12 + len;
  }
  const auto per_metre = static_cast<std::uint32_t>(std::lround(dpi / 0.0254));
  std::string chunk = "pHYs";
  put32(chunk, per_metre);
  put32(chunk, per_metre);
  chunk += '\x01';  // unit: the metre
  std::string out;
  put32(out, 9);
  out += chunk;
  put32(out, static_cast<std::uint32_t>(
                 crc32(0L, reinterpret_cast<const Bytef*>(chunk.data()), static_cast<uInt>(chunk.size()))));
  png.insert(kAfterIhdr, out);
  return png;
}

void write_plot_file(const std::filesystem::path& file, Format format,
                     const std::function<void(const std::filesystem::path& temporary)>& draw) {
  try {
    interchange::PendingFile pending(file);
    draw(pending.temporary());
    if (!ends_whole(read_bytes(pending.temporary()), format))
      throw std::runtime_error("cannot write " + file.string() + ": the figure came out incomplete (disk full?)");
    pending.commit();
  } catch (const std::system_error& e) {
    throw std::runtime_error(e.what());
  }
}

}  // namespace knoblab::fit::plot::detail
