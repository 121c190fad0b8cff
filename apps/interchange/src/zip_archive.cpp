// Zip layout (PKWARE APPNOTE 6.3): local file headers with the data, then
// the central directory, then the end-of-central-directory record (and,
// before it, the zip64 record and its locator when counts or offsets
// overflow 16/32 bits). The central directory is the authority; the local
// header is only used to skip its name and extra field.
#include "zip_archive.hpp"

#include <zlib.h>

#include <algorithm>
#include <climits>

#include "knoblab/interchange/mat5.hpp"

namespace knoblab::interchange::detail {

namespace {

constexpr std::uint32_t kEocdSig = 0x06054b50, kZip64EocdSig = 0x06064b50, kZip64LocatorSig = 0x07064b50,
                        kCentralSig = 0x02014b50, kLocalSig = 0x04034b50;
constexpr std::size_t kEocdBytes = 22, kCentralBytes = 46, kLocalBytes = 30;
constexpr std::uint32_t kOverflow32 = 0xffffffff;

}  // namespace

void ZipArchive::fail(std::size_t at, const std::string& reason) const { throw MatError(source_, at, reason); }

std::uint64_t ZipArchive::le(std::size_t at, std::size_t width) const {
  std::uint64_t v = 0;
  for (std::size_t i = width; i-- > 0;) v = (v << 8) | static_cast<unsigned char>(bytes_[at + i]);
  return v;
}

ZipArchive::ZipArchive(std::string_view bytes, const std::string& source, std::size_t max_members)
    : bytes_(bytes), source_(source) {
  // The end record sits in the last 22 bytes plus a comment of up to 64 KiB.
  if (bytes.size() < kEocdBytes) fail(0, "not a zip archive: too short for its end record");
  std::size_t eocd = std::string_view::npos;
  const std::size_t lowest = bytes.size() - kEocdBytes - std::min<std::size_t>(0xffff, bytes.size() - kEocdBytes);
  for (std::size_t at = bytes.size() - kEocdBytes + 1; at-- > lowest;)
    if (le(at, 4) == kEocdSig && at + kEocdBytes + le(at + 20, 2) == bytes.size()) {
      eocd = at;
      break;
    }
  if (eocd == std::string_view::npos)
    fail(bytes.size(), "not a zip archive, or truncated: no end-of-central-directory record at its end");
  if (le(eocd + 4, 2) != 0 || le(eocd + 6, 2) != 0) fail(eocd, "multi-disk zip archives are not supported");
  std::uint64_t count = le(eocd + 10, 2), dir_size = le(eocd + 12, 4), dir_at = le(eocd + 16, 4);
  if (count == 0xffff || dir_size == kOverflow32 || dir_at == kOverflow32) {
    if (eocd < 20 || le(eocd - 20, 4) != kZip64LocatorSig)
      fail(eocd, "end record says zip64, but no zip64 locator precedes it");
    const std::uint64_t z = le(eocd - 20 + 8, 8);
    if (z > eocd - 20 || eocd - 20 - z < 56 || le(z, 4) != kZip64EocdSig)
      fail(eocd - 20, "zip64 locator points at " + std::to_string(z) + ", where no zip64 end record is");
    const auto zat = static_cast<std::size_t>(z);
    count = le(zat + 32, 8);
    dir_size = le(zat + 40, 8);
    dir_at = le(zat + 48, 8);
  }
  if (dir_at > bytes.size() || dir_size > bytes.size() - dir_at)
    fail(eocd, "central directory (" + std::to_string(dir_size) + " bytes at " + std::to_string(dir_at) +
                   ") lies outside the file of " + std::to_string(bytes.size()) + " bytes");
  if (count > max_members)
    fail(eocd, std::to_string(count) + " members, over the limit of " + std::to_string(max_members));
  // Every entry needs 46 bytes: refuse counts the directory cannot hold before reserving.
  if (count > dir_size / kCentralBytes)
    fail(eocd, std::to_string(count) + " members claimed, but the central directory holds only " +
                   std::to_string(dir_size) + " bytes");

  std::size_t at = static_cast<std::size_t>(dir_at);
  const std::size_t end = at + static_cast<std::size_t>(dir_size);
  members_.reserve(static_cast<std::size_t>(count));
  for (std::uint64_t i = 0; i < count; ++i) {
    if (end - at < kCentralBytes || le(at, 4) != kCentralSig)
      fail(at, "central directory entry " + std::to_string(i + 1) + " is missing or broken");
    ZipMember m;
    m.entry_offset = at;
    m.flags = static_cast<std::uint16_t>(le(at + 8, 2));
    m.method = static_cast<std::uint16_t>(le(at + 10, 2));
    m.crc = static_cast<std::uint32_t>(le(at + 16, 4));
    m.compressed = le(at + 20, 4);
    m.size = le(at + 24, 4);
    const std::size_t name_len = le(at + 28, 2), extra_len = le(at + 30, 2), comment_len = le(at + 32, 2);
    m.local_offset = le(at + 42, 4);
    if (end - at - kCentralBytes < name_len + extra_len + comment_len)
      fail(at, "central directory entry " + std::to_string(i + 1) + " runs past the directory's end");
    m.name = std::string(bytes.substr(at + kCentralBytes, name_len));
    // zip64 extra field: 64-bit values for whichever of the fields above overflowed, in this order.
    std::size_t x = at + kCentralBytes + name_len;
    const std::size_t x_end = x + extra_len;
    while (x_end - x >= 4) {
      const auto id = le(x, 2), len = static_cast<std::size_t>(le(x + 2, 2));
      if (x_end - x - 4 < len) fail(x, "extra field of member '" + m.name + "' runs past its entry");
      if (id == 0x0001) {
        std::size_t p = x + 4;
        for (std::uint64_t* field : {&m.size, &m.compressed, &m.local_offset}) {
          if (*field != kOverflow32) continue;
          if (p + 8 > x + 4 + len) fail(x, "zip64 extra field of member '" + m.name + "' is too short");
          *field = le(p, 8);
          p += 8;
        }
      }
      x += 4 + len;
    }
    members_.push_back(std::move(m));
    at = x_end + comment_len;
  }
}

std::string ZipArchive::extract(const ZipMember& m, std::size_t max_bytes) const {
  const std::string who = "member '" + m.name + "'";
  if (m.flags & 1) fail(m.entry_offset, who + " is encrypted");
  if (m.method != 0 && m.method != 8)
    fail(m.entry_offset, who + ": compression method " + std::to_string(m.method) +
                             " (knoblab reads stored and deflated members, as np.savez and np.savez_compressed write)");
  if (m.size > max_bytes)
    fail(m.entry_offset, who + " extracts to " + std::to_string(m.size) + " bytes, over the " +
                             std::to_string(max_bytes) + "-byte limit");
  if (m.local_offset > bytes_.size() || bytes_.size() - m.local_offset < kLocalBytes ||
      le(static_cast<std::size_t>(m.local_offset), 4) != kLocalSig)
    fail(m.entry_offset, who + ": no local file header at offset " + std::to_string(m.local_offset));
  const auto local = static_cast<std::size_t>(m.local_offset);
  const std::size_t data = local + kLocalBytes + le(local + 26, 2) + le(local + 28, 2);
  if (data > bytes_.size() || bytes_.size() - data < m.compressed)
    fail(local, who + " is truncated: " + std::to_string(m.compressed) + " bytes of data claimed, " +
                    std::to_string(data > bytes_.size() ? 0 : bytes_.size() - data) + " present");
  const std::string_view in = bytes_.substr(data, static_cast<std::size_t>(m.compressed));

  std::string out;
  if (m.method == 0) {
    if (m.compressed != m.size) fail(m.entry_offset, who + " is stored, yet its two sizes differ");
    out = std::string(in);
  } else {
    out.resize(static_cast<std::size_t>(m.size));
    z_stream zs{};
    if (inflateInit2(&zs, -MAX_WBITS) != Z_OK) fail(data, "zlib inflateInit2 failed");
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    zs.avail_in = static_cast<uInt>(std::min<std::size_t>(in.size(), UINT_MAX));
    zs.next_out = reinterpret_cast<Bytef*>(out.data());
    zs.avail_out = static_cast<uInt>(std::min<std::size_t>(out.size(), UINT_MAX));
    const int rc = inflate(&zs, Z_FINISH);
    const std::size_t got = out.size() - zs.avail_out;
    const std::string msg = zs.msg ? std::string(" (zlib: ") + zs.msg + ")" : std::string();
    const bool more = zs.avail_out == 0 && rc != Z_STREAM_END;
    inflateEnd(&zs);
    if (more) fail(data, who + " inflates to more than the " + std::to_string(m.size) + " bytes its entry claims");
    if (rc != Z_STREAM_END || got != out.size())
      fail(data, who + " does not inflate to the " + std::to_string(m.size) + " bytes its entry claims" + msg);
  }
  const auto crc = crc32_z(0L, reinterpret_cast<const Bytef*>(out.data()), out.size());
  if (crc != m.crc) fail(data, who + ": CRC-32 mismatch (the archive is corrupt)");
  return out;
}

}  // namespace knoblab::interchange::detail
