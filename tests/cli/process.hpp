// Running the knoblab binary from a test, and scratch directories.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace knoblab::test {

struct RunResult {
  int exit_code = -1;  // -1 when killed by a signal
  std::string out, err;
};

// Runs knoblab with these arguments and waits for it.
RunResult run_knoblab(const std::vector<std::string>& args);

// Starts knoblab in the background (output discarded); returns its pid.
pid_t spawn_knoblab(const std::vector<std::string>& args);

// Polls `done` every 20 ms until it holds (true) or `within` has passed (false).
bool eventually(const std::function<bool()>& done, std::chrono::milliseconds within = std::chrono::seconds(20));

// Starts any program in the background, stdin from /dev/null, stdout and
// stderr into these files; returns its pid (-1 if it could not start).
pid_t spawn(const std::vector<std::string>& args, const std::string& out, const std::string& err);

// The exit code once the process ends within `within` (-1: killed by a
// signal), or nullopt after killing it for taking too long.
std::optional<int> wait_exit(pid_t pid, std::chrono::milliseconds within = std::chrono::seconds(20));

// A fresh directory under /tmp, removed with everything in it at scope exit.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

std::string read_file(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, const std::string& text);

}  // namespace knoblab::test
