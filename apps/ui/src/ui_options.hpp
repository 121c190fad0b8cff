// knoblab-ui's command line.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace knoblab::ui {

struct UiOptions {
  std::string socket = "/run/knoblab/hapticd.sock";
  std::string db = "/var/lib/knoblab/lab.sqlite";  // the store, read only (hapticd writes it)
  std::string knoblab = "knoblab";                  // the CLI that fits and finds discrepancies
  bool supervise = true;
  bool fullscreen = false;
  int width = 1280, height = 800;  // the window (or screenshot) size
  std::string screen = "home";     // the screen shown first
  // Render the first screen offscreen to this PNG, check its layout, exit.
  std::string screenshot;
  double wait_s = 5.0;  // for hapticd's first state before the screenshot
  // Every second, what the screen shows (its named texts) as JSON, written
  // atomically: how a test or a remote look tells what the kiosk displays.
  std::string status_file;
  // The study protocols offered (default: where the package installs them,
  // or, in a build tree, the copy of examples/studies beside the program).
  std::string studies;
  // Start this participant's session of this protocol at once; with
  // study_simulate in simulated time (hapticd's core and the simulated
  // participant, no hapticd), pausing at study_pause_at (target, counter,
  // freeform, sliders, texture, rating, trials:N): a dry run, and how the
  // screenshot tests show a real session.
  std::string study_protocol, study_participant = "P01", study_pause_at;
  bool study_simulate = false;
  // The prototyper's designs (thesis ch. 5) live here, beside the knob
  // library; --design opens one at start.
  std::string designs = "/var/lib/knoblab/designs";
  std::string design;
  bool help = false, version = false;
};

// Throws std::invalid_argument with a message for the user.
UiOptions parse_ui_options(const std::vector<std::string>& args);
std::string ui_usage();

}  // namespace knoblab::ui
