// .npz: np.savez writes each array as member "NAME.npy" of a zip archive
// (stored, or deflated by np.savez_compressed); np.load names it NAME.
#include "knoblab/interchange/npy.hpp"
#include "zip_archive.hpp"

namespace knoblab::interchange {

std::vector<MatArray> parse_npz(std::string_view bytes, std::string_view source_name, const MatLimits& limits) {
  const std::string source(source_name);
  const detail::ZipArchive zip(bytes, source, limits.max_arrays);
  std::vector<MatArray> out;
  for (const auto& m : zip.members()) {
    if (!m.name.ends_with(".npy"))
      throw MatError(source, m.entry_offset, "member '" + m.name + "' is not a .npy array (np.savez writes only those)");
    const std::string member = zip.extract(m, limits.max_inflated_bytes);
    try {
      out.push_back(parse_npy(member, source + ":" + m.name, limits));
    } catch (const MatError& e) {
      // Offsets inside a deflated member mean nothing in the archive: say where they are.
      throw MatError(source, m.entry_offset, "member '" + m.name + "', byte " + std::to_string(e.offset()) + ": " + e.reason());
    }
    out.back().name = m.name.substr(0, m.name.size() - 4);
  }
  return out;
}

}  // namespace knoblab::interchange
