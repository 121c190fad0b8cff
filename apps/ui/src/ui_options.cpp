#include "ui_options.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace knoblab::ui {

std::string ui_usage() {
  return "usage: knoblab-ui [--socket PATH] [--db FILE] [--knoblab PATH] [--no-supervise] [--fullscreen]\n"
         "                  [--size WxH] [--screen NAME] [--screenshot OUT.png [--wait SECONDS]]\n"
         "                  [--status-file FILE] [--studies DIR] [--designs DIR] [--design FILE]\n"
         "                  [--study PROTOCOL.json [--participant CODE] [--simulate [--pause-at WHAT]]]\n"
         "\n"
         "The knoblab touchscreen front-end. It talks to hapticd through its control socket\n"
         "(default /run/knoblab/hapticd.sock) and supervises it: if the UI stops, the motor\n"
         "goes safe (--no-supervise: watch only). It reads the store hapticd records into\n"
         "(--db, default /var/lib/knoblab/lab.sqlite) and runs fits and discrepancy with the\n"
         "knoblab command (--knoblab, default: knoblab on the PATH), which store their results\n"
         "there. Screens: home, system, capture, library, review (the newest capture),\n"
         "compare (the two newest), study (the experimenter's view of a user study),\n"
         "participant (the participant's view), prototyper (the Haptic Icon Prototyper).\n"
         "--designs names the folder of prototyper designs (default /var/lib/knoblab/designs);\n"
         "--design opens one (a path, or a file name in that folder).\n"
         "--studies names the folder of study protocols offered (default: the installed examples).\n"
         "--study starts CODE's session of the protocol (default P01; it resumes when it exists);\n"
         "--simulate runs it in simulated time with the simulated participant (no hapticd), pausing\n"
         "at --pause-at: target, counter, freeform, sliders, texture, rating or trials:N.\n"
         "--screenshot renders the first screen offscreen at --size, waits up to --wait s\n"
         "(default 5) for hapticd's state and the screen's job, writes the PNG, checks that no text is clipped and\n"
         "no QML warning was printed, and exits 0 (all well), 1 (a problem, printed) or 2.\n"
         "--status-file writes what the screen shows (its named texts) as JSON every second.\n";
}

UiOptions parse_ui_options(const std::vector<std::string>& args) {
  UiOptions o;
  auto need = [&](std::size_t& i) -> const std::string& {
    if (i + 1 >= args.size()) throw std::invalid_argument(args[i] + " needs a value");
    return args[++i];
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--socket") o.socket = need(i);
    else if (a == "--db") o.db = need(i);
    else if (a == "--knoblab") o.knoblab = need(i);
    else if (a == "--no-supervise") o.supervise = false;
    else if (a == "--fullscreen") o.fullscreen = true;
    else if (a == "--screen") o.screen = need(i);
    else if (a == "--screenshot") o.screenshot = need(i);
    else if (a == "--status-file") o.status_file = need(i);
    else if (a == "--studies") o.studies = need(i);
    else if (a == "--study") o.study_protocol = need(i);
    else if (a == "--participant") o.study_participant = need(i);
    else if (a == "--simulate") o.study_simulate = true;
    else if (a == "--pause-at") o.study_pause_at = need(i);
    else if (a == "--designs") o.designs = need(i);
    else if (a == "--design") o.design = need(i);
    else if (a == "--help" || a == "-h") o.help = true;
    else if (a == "--version") o.version = true;
    else if (a == "--size") {
      const std::string& v = need(i);
      int w = 0, h = 0;
      char extra = 0;
      if (std::sscanf(v.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 320 || h < 240 || w > 7680 || h > 4320)
        throw std::invalid_argument("--size must be WIDTHxHEIGHT in pixels (320x240 … 7680x4320), got '" + v + "'");
      o.width = w, o.height = h;
    } else if (a == "--wait") {
      const std::string& v = need(i);
      char* end = nullptr;
      o.wait_s = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end || !(o.wait_s >= 0 && o.wait_s <= 600))
        throw std::invalid_argument("--wait must be seconds in 0 … 600, got '" + v + "'");
    } else {
      throw std::invalid_argument("unknown option '" + a + "'");
    }
  }
  if (o.studies.empty()) {
    // Installed, or beside the program in a build tree (the build copies
    // examples/studies there): no path of the checkout is built in.
    std::error_code ec;
    const auto beside = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / "studies";
    o.studies = std::filesystem::is_directory(KNOBLAB_UI_STUDIES_DIR) || ec ? KNOBLAB_UI_STUDIES_DIR
                                                                            : beside.string();
  }
  return o;
}

}  // namespace knoblab::ui
