#include "knoblab/interchange/array_file.hpp"

#include <fstream>
#include <system_error>

#include "file_bytes.hpp"
#include "knoblab/interchange/npy.hpp"

namespace knoblab::interchange {

namespace detail {

std::string read_file_bytes(const std::filesystem::path& path, const MatLimits& limits) {
  const std::string source = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw MatError(source, 0, "is a directory", true);
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw MatError(source, 0, "cannot read: " + ec.message(), true);
  if (size > limits.max_file_bytes)
    throw MatError(source, 0, "file of " + std::to_string(size) + " bytes is over the " +
                                  std::to_string(limits.max_file_bytes) + "-byte limit", true);
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in || !in.read(bytes.data(), static_cast<std::streamsize>(size)))
    throw MatError(source, 0, "cannot read the file", true);
  return bytes;
}

}  // namespace detail

ArrayFileKind array_file_kind(std::string_view b) {
  // Not just "MATLAB": a CSV's first column may be called that.
  if (b.starts_with("MATLAB 5.0 MAT-file") || b.starts_with("MATLAB 7.3 MAT-file")) return ArrayFileKind::kMat;
  if (b.starts_with(std::string_view("\x93NUMPY", 6))) return ArrayFileKind::kNpy;
  // A Python pickle (np.save of an object, or pickle.dump): the .npy reader refuses it by name.
  if (b.size() >= 2 && static_cast<unsigned char>(b[0]) == 0x80 && b[1] >= 2 && b[1] <= 5) return ArrayFileKind::kNpy;
  if (b.starts_with("PK\x03\x04") || b.starts_with("PK\x05\x06")) return ArrayFileKind::kNpz;
  return ArrayFileKind::kNone;
}

std::vector<MatArray> read_array_file(const std::filesystem::path& path, const MatLimits& limits) {
  const std::string source = path.string();
  const std::string bytes = detail::read_file_bytes(path, limits);
  switch (array_file_kind(bytes)) {
    case ArrayFileKind::kMat: return parse_mat(bytes, source, limits);
    case ArrayFileKind::kNpz: return parse_npz(bytes, source, limits);
    case ArrayFileKind::kNpy: {
      std::vector<MatArray> one{parse_npy(bytes, source, limits)};
      one[0].name = path.stem().string();
      return one;
    }
    case ArrayFileKind::kNone: break;
  }
  // Named as one of them: that reader says what is wrong with it.
  const std::string ext = path.extension().string();
  if (ext == ".mat") return parse_mat(bytes, source, limits);
  if (ext == ".npy") return {parse_npy(bytes, source, limits)};
  if (ext == ".npz") return parse_npz(bytes, source, limits);
  throw MatError(source, 0, "not a MAT, .npy or .npz file (its first bytes are none of theirs)", true);
}

MatArray take_array(std::vector<MatArray>& arrays, std::string_view name, const std::string& source) {
  std::string present;
  for (auto& v : arrays) {
    if (v.name == name) return std::move(v);
    present += (present.empty() ? "" : ", ") + v.name + " (" + v.describe() + ")";
  }
  throw MatError(source, 0,
                 "no variable '" + std::string(name) + "'; the file holds " +
                     (present.empty() ? "no variables" : present),
                 true);
}

}  // namespace knoblab::interchange
