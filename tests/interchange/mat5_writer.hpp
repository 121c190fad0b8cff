// Test-only MAT v5 writer: just enough to build files byte by byte, in either
// byte order, including the broken ones the reader must refuse.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace knoblab::test::mat5 {

enum : std::uint32_t {
  miINT8 = 1, miUINT8 = 2, miINT16 = 3, miUINT16 = 4, miINT32 = 5, miUINT32 = 6,
  miSINGLE = 7, miDOUBLE = 9, miMATRIX = 14, miCOMPRESSED = 15,
};
enum : std::uint32_t {
  mxCELL = 1, mxSTRUCT = 2, mxCHAR = 4, mxSPARSE = 5, mxDOUBLE = 6, mxSINGLE = 7,
  mxINT8 = 8, mxUINT8 = 9, mxINT16 = 10,
};

class Writer {
 public:
  explicit Writer(bool big_endian = false) : big_(big_endian) {}

  // The 128-byte header: text, no subsystem data, version 0x0100, "IM"/"MI".
  std::string header(const std::string& text = "MATLAB 5.0 MAT-file, knoblab test") const {
    std::string h = text;
    h.resize(116, ' ');
    h.append(8, '\0');
    h += uint(0x0100, 2);
    h += big_ ? "MI" : "IM";
    return h;
  }

  // An unsigned integer of `width` bytes in the file's byte order.
  std::string uint(std::uint64_t v, std::size_t width) const {
    std::string s(width, '\0');
    for (std::size_t i = 0; i < width; ++i)
      s[big_ ? width - 1 - i : i] = static_cast<char>((v >> (8 * i)) & 0xff);
    return s;
  }

  std::string tag(std::uint32_t type, std::uint32_t size) const { return uint(type, 4) + uint(size, 4); }

  // A data element padded to 8 bytes.
  std::string element(std::uint32_t type, const std::string& data) const {
    std::string e = tag(type, static_cast<std::uint32_t>(data.size())) + data;
    e.resize((e.size() + 7) / 8 * 8, '\0');
    return e;
  }

  // The small format: size and type share the first 4 bytes, data the next 4.
  std::string small_element(std::uint32_t type, const std::string& data) const {
    std::string e = uint((static_cast<std::uint64_t>(data.size()) << 16) | type, 4) + data;
    e.resize(8, '\0');
    return e;
  }

  template <class T>
  std::string values(const std::vector<T>& v) const {
    std::string s;
    for (T x : v) {
      if constexpr (sizeof(T) == 8) s += uint(std::bit_cast<std::uint64_t>(x), 8);
      else if constexpr (sizeof(T) == 4) s += uint(std::bit_cast<std::uint32_t>(x), 4);
      else if constexpr (sizeof(T) == 2) s += uint(std::bit_cast<std::uint16_t>(x), 2);
      else s += uint(std::bit_cast<std::uint8_t>(x), 1);
    }
    return s;
  }

  // An miMATRIX element: flags, dims, name, then `body` (data or cells).
  std::string matrix(const std::string& name, std::uint32_t mx_class, const std::vector<std::int32_t>& dims,
                     const std::string& body, std::uint32_t flag_bits = 0) const {
    std::string m = element(miUINT32, uint(mx_class | flag_bits, 4) + uint(0, 4));
    m += element(miINT32, values(dims));
    m += name.size() <= 4 ? small_element(miINT8, name) : element(miINT8, name);
    return element(miMATRIX, m + body);
  }

  std::string doubles(const std::string& name, std::int32_t rows, std::int32_t cols,
                      const std::vector<double>& v) const {
    return matrix(name, mxDOUBLE, {rows, cols}, element(miDOUBLE, values(v)));
  }

  std::string cell(const std::string& name, std::int32_t rows, std::int32_t cols,
                   const std::vector<std::string>& cells) const {
    std::string body;
    for (const auto& c : cells) body += c;
    return matrix(name, mxCELL, {rows, cols}, body);
  }

 private:
  bool big_;
};

}  // namespace knoblab::test::mat5
