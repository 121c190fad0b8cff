#include "result_files.hpp"

#include <stdlib.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "knoblab/interchange/atomic_file.hpp"

namespace knoblab::cli {

StagedReport::StagedReport() {
  std::string tmpl = (std::filesystem::temp_directory_path() / "knoblab-report-XXXXXX").string();
  if (!::mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a scratch directory in " +
                                                        std::filesystem::temp_directory_path().string());
  dir_ = tmpl;
}

StagedReport::~StagedReport() {
  std::error_code ec;
  std::filesystem::remove_all(dir_, ec);
}

void StagedReport::add(const std::string& name, std::string_view bytes) const {
  interchange::write_file_atomically(dir_ / name, bytes);
}

std::vector<store::ResultFile> StagedReport::files() const {
  std::vector<store::ResultFile> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + entry.path().string());
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    store::ResultFile f{entry.path().filename().string(), {}};
    f.bytes.assign(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                   reinterpret_cast<const std::uint8_t*>(bytes.data()) + bytes.size());
    out.push_back(std::move(f));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return out;
}

bool plain_file_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." &&
         name.find_first_of(std::string("/\0", 2)) == std::string::npos;
}

void write_result_files(const std::vector<store::ResultFile>& files, const std::filesystem::path& dir) {
  for (const auto& f : files)
    if (!plain_file_name(f.name))
      throw std::runtime_error("refusing to write a file named '" + f.name + "'");
  std::filesystem::create_directories(dir);
  for (const auto& f : files)
    interchange::write_file_atomically(
        dir / f.name, std::string_view(reinterpret_cast<const char*>(f.bytes.data()), f.bytes.size()));
}

std::size_t total_bytes(const std::vector<store::ResultFile>& files) {
  std::size_t n = 0;
  for (const auto& f : files) n += f.bytes.size();
  return n;
}

}  // namespace knoblab::cli
