// A report PNG decoded to RGB on white (libpng's simplified API), for tests
// that check what a plot drew: count pixels of a colour, find a band.
#pragma once

#include <png.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace knoblab::testing {

struct Image {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes a pixel, on white
  std::array<int, 3> at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

inline Image decode_png(const std::filesystem::path& file) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, file.c_str()))
    throw std::runtime_error("cannot read " + file.string());
  img.format = PNG_FORMAT_RGB;
  Image out;
  out.width = img.width;
  out.height = img.height;
  out.rgb.resize(PNG_IMAGE_SIZE(img));
  png_color white{255, 255, 255};
  if (!png_image_finish_read(&img, &white, out.rgb.data(), 0, nullptr))
    throw std::runtime_error("cannot decode " + file.string());
  return out;
}

}  // namespace knoblab::testing
