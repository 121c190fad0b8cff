// A result's report files on their way out: drawn into a scratch directory
// first (a run cancelled or failing while it draws leaves nothing in the
// report directory), then, once the result is complete, written into the
// report directory and stored with the result, byte for byte the same.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/store/types.hpp"

namespace knoblab::cli {

class StagedReport {
 public:
  StagedReport();   // a fresh scratch directory under the temp directory
  ~StagedReport();  // removed with everything in it
  StagedReport(const StagedReport&) = delete;
  StagedReport& operator=(const StagedReport&) = delete;

  // Where the report writer draws.
  const std::filesystem::path& dir() const { return dir_; }
  // One more file beside what was drawn (fit.json).
  void add(const std::string& name, std::string_view bytes) const;
  // Everything in the directory, by name.
  std::vector<store::ResultFile> files() const;

 private:
  std::filesystem::path dir_;
};

// One plain file name, as the store's schema allows: not empty, no '/', no
// NUL, not "." or "..". Writing checks every name before the first file.
bool plain_file_name(const std::string& name);

// Writes each file into `dir` (created if missing), each replaced whole;
// files already there under other names stay. Throws std::runtime_error
// for a name that is not a plain file name (a store from elsewhere),
// before writing anything.
void write_result_files(const std::vector<store::ResultFile>& files, const std::filesystem::path& dir);

// The total size of the files, bytes.
std::size_t total_bytes(const std::vector<store::ResultFile>& files);

}  // namespace knoblab::cli
