#include "terminal.hpp"

#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>

namespace knoblab::test {

TerminalRun::TerminalRun(const std::vector<std::string>& args, const std::filesystem::path& tmpdir) {
  std::vector<std::string> argv_s = {KNOBLAB_CLI_PATH};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  struct winsize ws {};
  ws.ws_row = 24;
  ws.ws_col = 200;
  pid_ = ::forkpty(&master_, nullptr, nullptr, &ws);
  if (pid_ < 0) throw std::runtime_error("forkpty failed");
  if (pid_ == 0) {
    if (!tmpdir.empty()) ::setenv("TMPDIR", tmpdir.c_str(), 1);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
}

TerminalRun::~TerminalRun() {
  if (!reaped_ && pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  if (master_ >= 0) ::close(master_);
}

bool TerminalRun::read_some(std::chrono::milliseconds wait) {
  pollfd p{master_, POLLIN, 0};
  const int n = ::poll(&p, 1, static_cast<int>(wait.count()));
  if (n <= 0) return true;  // nothing yet
  char buf[4096];
  const ssize_t got = ::read(master_, buf, sizeof buf);
  if (got < 0 && errno == EINTR) return true;
  if (got <= 0) return false;  // EIO: every slave end is closed
  out_.append(buf, static_cast<std::size_t>(got));
  return true;
}

bool TerminalRun::wait_for(const std::string& text, std::chrono::milliseconds within) {
  const auto deadline = std::chrono::steady_clock::now() + within;
  while (out_.find(text) == std::string::npos) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    if (!read_some(std::chrono::milliseconds(50))) return out_.find(text) != std::string::npos;
  }
  return true;
}

int TerminalRun::finish(std::chrono::milliseconds within) {
  const auto deadline = std::chrono::steady_clock::now() + within;
  while (read_some(std::chrono::milliseconds(50))) {
    if (std::chrono::steady_clock::now() > deadline) return -2;
  }
  int status = 0;
  ::waitpid(pid_, &status, 0);
  reaped_ = true;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace knoblab::test
