// Running the knoblab binary on a pseudo-terminal, as a person at a shell
// does: its stdout and stderr are the terminal, so it draws its progress
// line, and the test reads what the screen would show.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace knoblab::test {

class TerminalRun {
 public:
  // Starts knoblab with these arguments on a new pty; TMPDIR set to `tmpdir`
  // when given (where it keeps scratch files).
  explicit TerminalRun(const std::vector<std::string>& args, const std::filesystem::path& tmpdir = {});
  ~TerminalRun();  // kills and reaps it if still running
  TerminalRun(const TerminalRun&) = delete;
  TerminalRun& operator=(const TerminalRun&) = delete;

  pid_t pid() const { return pid_; }
  // Reads the terminal until its output holds `text` (true) or the program
  // ends or `within` passes (false).
  bool wait_for(const std::string& text, std::chrono::milliseconds within = std::chrono::seconds(60));
  // Reads to the end and returns the exit code (-1: killed by a signal),
  // or -2 when it did not end within `within` (then it is killed).
  int finish(std::chrono::milliseconds within = std::chrono::seconds(60));
  const std::string& output() const { return out_; }

 private:
  bool read_some(std::chrono::milliseconds wait);  // false once the pty is closed
  pid_t pid_ = -1;
  int master_ = -1;
  std::string out_;
  bool reaped_ = false;
};

}  // namespace knoblab::test
