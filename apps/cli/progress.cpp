#include "progress.hpp"

#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include <nlohmann/json.hpp>

#include "cancel.hpp"

namespace knoblab::cli {

Progress::Progress(std::string command, bool enabled, std::FILE* out, Style style)
    : command_(std::move(command)), enabled_(enabled), out_(out), style_(style) {}

Progress Progress::on_stderr(const Args& args, std::string command) {
  const char* env = std::getenv("KNOBLAB_PROGRESS");
  if (env && std::strcmp(env, "json") == 0) return Progress(std::move(command), true, stderr, Style::json);
  return Progress(std::move(command), !args.has("quiet") && ::isatty(STDERR_FILENO) == 1);
}

Progress::~Progress() { clear(); }

void Progress::show(std::string_view stage, std::size_t done, std::size_t total) {
  if (!enabled_) return;
  std::string line = "knoblab " + command_ + ": " + std::string(stage);
  if (total > 1000)
    line += ": " + std::to_string(done * 100 / total) + " %";
  else if (total > 0)
    line += ": " + std::to_string(done) + " of " + std::to_string(total);
  if (line == shown_) return;  // a count that moved less than a percent
  if (style_ == Style::json) {
    // One line per step, nothing to erase.
    const nlohmann::json j = {
        {"progress", {{"command", command_}, {"stage", stage}, {"done", done}, {"total", total}}}};
    std::fprintf(out_, "%s\n", j.dump().c_str());
    std::fflush(out_);
    shown_ = std::move(line);
    return;
  }
  // \r back to the start, \033[K erase the rest of the old line.
  std::fprintf(out_, "\r%s\033[K", line.c_str());
  std::fflush(out_);
  shown_ = std::move(line);
}

void Progress::clear() {
  if (shown_.empty()) return;
  if (style_ == Style::json) return;  // lines stay; the next step is a new one
  std::fputs("\r\033[K", out_);
  std::fflush(out_);
  shown_.clear();
}

fit::RunHooks Progress::hooks() {
  fit::RunHooks h;
  h.progress = [this](std::string_view stage, std::size_t done, std::size_t total) {
    show(stage, done, total);
  };
  h.cancelled = [] { return cancel_requested(); };
  return h;
}

}  // namespace knoblab::cli
