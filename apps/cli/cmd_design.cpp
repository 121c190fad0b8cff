// knoblab design: prototyper designs from the command line (docs/designs.md):
// check one as hapticd would, export its render model and import one back,
// and play one on the simulated knob into a capture.
#include <filesystem>
#include <format>
#include <numbers>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "design_render.hpp"
#include "knoblab/design/design_json.hpp"
#include "knoblab/design/render_tiles.hpp"
#include "knoblab/interchange/atomic_file.hpp"
#include "knoblab/interchange/csv.hpp"

namespace knoblab::cli {

const CommandSpec kDesignSpec{
    "design",
    "check DESIGN.json | export DESIGN.json --out MODEL.json | import MODEL.json --out DESIGN.json [--name NAME] |\n"
    "       render DESIGN.json --out CAPTURE.csv [--seconds S] [--rate HZ] [--knob PRESET] [--torque sensor|knob]",
    "Check, export, import and play Haptic Icon Prototyper designs.\n"
    "check: reads the design (errors name the key) and says what it holds and whether\n"
    "hapticd would play it, or why not (exit 1).\n"
    "export: the design's render model, the arguments of hapticd's load_tiles\n"
    "(docs/protocol.md): the active lines of the channels that play.\n"
    "import: a render model back into a design, one line per channel.\n"
    "render: plays the design in hapticd's core on the sim backend, in simulated time,\n"
    "while a simulated hand turns the knob slowly from 0 to one end of the design's\n"
    "range, across to the other and back, and writes every cycle as a capture CSV\n"
    "(docs/interchange.md) that knoblab import, fit and discrepancy take; with --torque knob\n"
    "its torque is the one it takes to turn the knob, the sign they read a knob's torque in.",
    {{"out", true, "the file to write", "FILE"},
     {"name", true, "import: the design's name (default: the file's stem)"},
     {"seconds", true, "render: how long the hand turns the knob (default 20)"},
     {"rate", true, "render: the loop rate in Hz (default 10000)"},
     {"knob", true, "render: the sim preset on the motor (default study3-not-rendered, the haptic knob itself)"},
     {"torque", true,
      "render: sensor (default: the torque sensor's reading, the motor's push on the knob, as hapticd records it) "
      "or knob (the torque it takes to turn the knob: the sensor's negated, as fit and discrepancy read it)",
      "sensor|knob"}},
    2, 2, false,
    {"knoblab design check examples/designs/fan-knob.json",
     "knoblab design export examples/designs/fan-knob.json --out fan-knob.tiles.json",
     "knoblab design import fan-knob.tiles.json --out fan-knob-again.json --name \"fan knob\"",
     "knoblab design render examples/designs/fan-knob.json --seconds 20 --out fan-knob.csv",
     "knoblab design render examples/designs/fan-knob.json --seconds 8 --torque knob --out fan-knob.knob.csv"}};

namespace {

design::Design read(const std::string& path) { return design::read_design(path); }

void write_json(const std::string& path, const nlohmann::json& j) {
  interchange::write_file_atomically(path, j.dump(2) + "\n");
}

int check(const std::string& path) {
  const design::Design d = read(path);
  std::cout << std::format("{}: \"{}\", {} palette tab(s)\n", path, d.name, d.palette.size());
  for (const design::Channel c : design::kChannels) {
    const design::ChannelLines& cl = d.lines(c);
    std::size_t tiles = 0;
    for (const design::Line& line : cl.lines) tiles += line.tiles.size();
    std::cout << std::format("  {:<12} {} line(s), {} tile(s){}\n", design::channel_name(c), cl.lines.size(), tiles,
                             cl.play ? "" : " (not played)");
  }
  const std::string refusal = design_render_refusal(d);
  if (refusal.empty()) {
    std::cout << "hapticd would play it.\n";
    return 0;
  }
  std::cout << "hapticd would refuse it: " << refusal << "\n";
  return 1;
}

int import_model(const Args& args, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  }
  design::Design d;
  try {
    d = design::design_from_load_tiles(j, args.get("name").value_or(std::filesystem::path(path).stem().string()));
  } catch (const jsonread::PathError& e) {
    throw e.in_file(path);
  }
  design::write_design(args.require("out"), d);
  std::cout << "wrote " << args.require("out") << "\n";
  return 0;
}

int render(const Args& args, const std::string& path) {
  DesignRenderRequest request;
  request.design = read(path);
  request.seconds = args.number("seconds", request.seconds);
  request.rate_hz = args.number("rate", request.rate_hz);
  request.knob = args.get("knob").value_or(request.knob);
  if (const auto torque = args.get("torque")) {
    if (*torque == "knob") request.torque = RenderedTorque::Knob;
    else if (*torque != "sensor") throw UsageError("--torque must be sensor or knob, not '" + *torque + "'");
  }
  const DesignRenderResult r = render_design(request);
  interchange::write_csv(r.capture, std::filesystem::path(args.require("out")));
  std::cout << std::format("wrote {}: {} samples, the knob turned across {:.1f}° … {:.1f}° and back\n",
                           args.require("out"), r.capture.size(), r.range_from * 180.0 / std::numbers::pi,
                           r.range_to * 180.0 / std::numbers::pi);
  return 0;
}

}  // namespace

int run_design(const Args& args) {
  const std::string& action = args.positionals().at(0);
  const std::string& file = args.positionals().at(1);
  if (action == "check") return check(file);
  if (action == "export") {
    write_json(args.require("out"), design::load_tiles_args(read(file)));
    std::cout << "wrote " << args.require("out") << "\n";
    return 0;
  }
  if (action == "import") return import_model(args, file);
  if (action == "render") return render(args, file);
  throw UsageError("unknown design action '" + action + "' (check, export, import, render)");
}

}  // namespace knoblab::cli
