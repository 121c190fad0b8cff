// The one-line progress indicator of a long command on stderr:
//
//   knoblab discrepancy: trying candidates, round 1: 3 of 15
//
// redrawn in place (carriage return, erase to the end of the line) as the
// command moves on. Drawn only when stderr is a terminal and --quiet was
// not given: a pipe, a file or a test sees nothing. Erased before the
// command prints its results, and when it ends.
//
// A program running knoblab (knoblab-ui) sets KNOBLAB_PROGRESS=json and gets
// each step as one JSON line on stderr instead, whatever stderr is:
//
//   {"progress":{"command":"discrepancy","stage":"trying candidates, round 1","done":3,"total":15}}
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

#include "args.hpp"
#include "knoblab/fit/run_hooks.hpp"

namespace knoblab::cli {

class Progress {
 public:
  enum class Style { line, json };
  // Draws on `out` when `enabled`.
  Progress(std::string command, bool enabled, std::FILE* out = stderr, Style style = Style::line);
  // Enabled when stderr is a terminal and the command has no --quiet; JSON
  // lines whenever KNOBLAB_PROGRESS=json.
  static Progress on_stderr(const Args& args, std::string command);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  bool enabled() const { return enabled_; }
  // "stage", or "stage: done of total" (a percentage beyond 1000 steps).
  void show(std::string_view stage, std::size_t done = 0, std::size_t total = 0);
  void clear();  // erases the line, if one is drawn

  // Hooks for a fit or a discovery: progress shown here, cancellation by
  // cancel.hpp's flag.
  fit::RunHooks hooks();

 private:
  std::string command_;
  bool enabled_;
  std::FILE* out_;
  Style style_;
  std::string shown_;  // the line on screen, empty when none
};

// The --quiet option every command with a progress line takes.
inline const OptionSpec kQuietOption{"quiet", false, "no progress line on stderr"};

}  // namespace knoblab::cli
