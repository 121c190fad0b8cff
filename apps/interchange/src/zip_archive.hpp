// Reading members of a zip archive held in memory (what a .npz file is):
// the central directory (zip64 too, as np.savez always writes), stored and
// deflated members, CRC-checked. Encrypted and multi-disk archives and other
// compression methods are refused. Errors are MatErrors naming the offset.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace knoblab::interchange::detail {

struct ZipMember {
  std::string name;
  std::uint16_t method = 0;      // 0 stored, 8 deflated
  std::uint16_t flags = 0;       // general purpose bits (bit 0: encrypted)
  std::uint32_t crc = 0;
  std::uint64_t compressed = 0;  // bytes in the archive
  std::uint64_t size = 0;        // bytes once extracted
  std::uint64_t local_offset = 0;
  std::size_t entry_offset = 0;  // of its central directory entry, for messages
};

class ZipArchive {
 public:
  // Reads the central directory; throws MatError if there is none or it is
  // broken. `bytes` must outlive the archive.
  ZipArchive(std::string_view bytes, const std::string& source, std::size_t max_members);

  const std::vector<ZipMember>& members() const { return members_; }

  // The member's bytes, refused when it would extract to more than max_bytes.
  std::string extract(const ZipMember& m, std::size_t max_bytes) const;

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& reason) const;
  std::uint64_t le(std::size_t at, std::size_t width) const;

  std::string_view bytes_;
  const std::string& source_;
  std::vector<ZipMember> members_;
};

}  // namespace knoblab::interchange::detail
