// Test-only NumPy writers: .npy bytes with any header text, dtype and byte
// order, and zip archives (stored or deflated, zip64 members like
// np.savez's), including the broken ones the readers must refuse.
#pragma once

#include <zlib.h>

#include <bit>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace knoblab::test::npy {

inline std::string le(std::uint64_t v, std::size_t width) {
  std::string s(width, '\0');
  for (std::size_t i = 0; i < width; ++i) s[i] = static_cast<char>((v >> (8 * i)) & 0xff);
  return s;
}

// Magic, version, header length and `header` padded with spaces and '\n' to
// a multiple of 64 bytes, as numpy writes it.
inline std::string preamble(const std::string& header, int major = 1) {
  const std::size_t len_bytes = major == 1 ? 2 : 4;
  std::string h = header;
  const std::size_t total = 8 + len_bytes + h.size() + 1;
  h.append((64 - total % 64) % 64, ' ');
  h += '\n';
  return std::string("\x93NUMPY", 6) + static_cast<char>(major) + '\0' + le(h.size(), len_bytes) + h;
}

inline std::string header(const std::string& descr, const std::string& shape, bool fortran = false) {
  return "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': " + shape +
         ", }";
}

// Values as `width`-byte items (float when is_float, else two's complement
// integers), in the given byte order.
inline std::string data(const std::vector<double>& v, std::size_t width, bool is_float, bool big_endian = false) {
  std::string s;
  for (double x : v) {
    std::uint64_t u = 0;
    if (is_float && width == 8) u = std::bit_cast<std::uint64_t>(x);
    else if (is_float) u = std::bit_cast<std::uint32_t>(static_cast<float>(x));
    else u = static_cast<std::uint64_t>(static_cast<std::int64_t>(x));
    std::string item = le(u, width);
    if (big_endian) item = std::string(item.rbegin(), item.rend());
    s += item;
  }
  return s;
}

// A float64 array in C order: the common case.
inline std::string f8(const std::string& shape, const std::vector<double>& v) {
  return preamble(header("<f8", shape)) + data(v, 8, true);
}

struct Member {
  std::string name;
  std::string bytes;
  bool deflate = false;
};

// A zip archive as Python's zipfile writes np.savez's: each local header
// with zip64 sizes (0xffffffff in the 32-bit fields), the central directory
// with plain ones. `corrupt_crc` flips the recorded CRC of every member.
inline std::string zip(const std::vector<Member>& members, bool corrupt_crc = false) {
  std::string out, dir;
  for (const auto& m : members) {
    std::string stored = m.bytes;
    if (m.deflate) {
      z_stream zs{};
      deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
      stored.assign(deflateBound(&zs, static_cast<uLong>(m.bytes.size())), '\0');
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(m.bytes.data()));
      zs.avail_in = static_cast<uInt>(m.bytes.size());
      zs.next_out = reinterpret_cast<Bytef*>(stored.data());
      zs.avail_out = static_cast<uInt>(stored.size());
      deflate(&zs, Z_FINISH);
      stored.resize(zs.total_out);
      deflateEnd(&zs);
    }
    std::uint32_t crc = static_cast<std::uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(m.bytes.data()), static_cast<uInt>(m.bytes.size())));
    if (corrupt_crc) crc ^= 1;
    const std::uint16_t method = m.deflate ? 8 : 0;
    const std::string zip64 = le(1, 2) + le(16, 2) + le(m.bytes.size(), 8) + le(stored.size(), 8);
    const std::size_t offset = out.size();
    out += le(0x04034b50, 4) + le(45, 2) + le(0, 2) + le(method, 2) + le(0, 4) + le(crc, 4) + le(0xffffffff, 4) +
           le(0xffffffff, 4) + le(m.name.size(), 2) + le(zip64.size(), 2) + m.name + zip64 + stored;
    dir += le(0x02014b50, 4) + le(45, 2) + le(45, 2) + le(0, 2) + le(method, 2) + le(0, 4) + le(crc, 4) +
           le(stored.size(), 4) + le(m.bytes.size(), 4) + le(m.name.size(), 2) + le(0, 2) + le(0, 2) + le(0, 2) +
           le(0, 2) + le(0, 4) + le(offset, 4) + m.name;
  }
  const std::size_t dir_at = out.size();
  return out + dir + le(0x06054b50, 4) + le(0, 2) + le(0, 2) + le(members.size(), 2) + le(members.size(), 2) +
         le(dir.size(), 4) + le(dir_at, 4) + le(0, 2);
}

}  // namespace knoblab::test::npy
