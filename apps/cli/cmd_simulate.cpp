// knoblab simulate: a Haptic Camera capture of a simulated knob.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <sstream>

#include "cancel.hpp"
#include "commands.hpp"
#include "knob_file.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/sim/presets.hpp"
#include "progress.hpp"
#include "simulation.hpp"
#include "summary.hpp"

namespace knoblab::cli {

const CommandSpec kSimulateSpec{
    "simulate",
    "(--knob PRESET | --params FIT.json) [--effects SPECS] [--seconds S] [--rate HZ]\n"
    "       [--out FILE.csv] [--db FILE.sqlite]",
    "Capture a simulated knob through the loop hapticd runs.\n"
    "The swept sine of thesis Eq. 8 (Table 3 spatial test by default) is tracked by the\n"
    "PID of Eq. 4 through the plant simulator. Writes an interchange CSV and/or a capture in the store; the CSV's\n"
    "flags column holds the loop's per-sample flags (docs/interchange.md).\n"
    "Eq. 8's frequency, u/d Hz with u = (b-a)*t/d + a, keeps rising past t = d: the\n"
    "default sweep runs at t/6 Hz, 1 Hz at 6 s but 10 Hz (63 rad/s at 1 rad) at 60 s.\n"
    "For a long capture, slow it down: --sweep 0,90,1,60 ends at 1.5 Hz at 60 s.\n"
    "The capture fails (exit status 1, saying where, why and what to change) when\n"
    "hapticd's supervisor stops it: the knob faster than 50 rad/s (velocity), or\n"
    "tracking lost (tracking): the knob more than 10 % of the sweep amplitude c, and\n"
    "at least 0.01 rad, off the sweep for 20 ms running, e.g. when it needs more than\n"
    "the 180 mN·m torque limit. The samples up to there are still written, with\n"
    "'# status: incomplete' and '# end_reason: fault: …' (the store marks the capture\n"
    "incomplete the same way).\n"
    "Ctrl-C cancels it: no CSV is written and the store keeps nothing of it (exit\n"
    "status 130).\n"
    "Presets: 'knoblab simulate --list'.",
    {{"knob", true, "knob preset id (see --list)", "PRESET"},
     {"effects", true, "effects beyond the thesis model, 'id:name=value,…;…', the names discrepancy reports (docs/discrepancy.md)", "SPECS"},
     {"params", true, "a fit's result JSON, a render model, or a model file with effects (discrepancy --model-out)"},
     {"seconds", true, "capture length, s (default 5, as the thesis)"},
     {"rate", true, "loop rate, Hz (default 5000; 1..20000)"},
     {"seed", true, "noise seed (default 1)"},
     {"out", true, "write the capture as interchange CSV"},
     {"db", true, "write the capture into this sqlite store"},
     {"mode", true, "lab (axis horizontal, default) or tripod", "lab|tripod"},
     {"tilt", true, "tripod: axis tilt from vertical, degrees (default 30)", "DEG"},
     {"amp", true, "amplifier mode: current (default) or voltage (Eq. 3)", "current|voltage"},
     {"kp", true, "PID Kp, V/rad (default 200)"},
     {"ki", true, "PID Ki, V/(rad·s) (default 5000)"},
     {"kd", true, "PID Kd, V·s/rad (default 1.0)"},
     {"sweep", true, "Eq. 8 constants a,b,c,d (default 0,1.5,1.0,3.0)", "A,B,C,D"},
     {"list", false, "list the knob presets and exit"},
     kQuietOption},
    0, 0, false,
    {"knoblab simulate --knob moderate-detents --out knob.csv",
     "knoblab simulate --params fit.json --seconds 10 --db lab.sqlite",
     "knoblab simulate --knob high-friction --effects 'stribeck:static_excess_Nm=0.004,stribeck_velocity_rad_s=0.5' --out sticky.csv"}};

namespace {

model::SweptSine parse_sweep(const std::string& text) {
  double v[4];
  std::istringstream in(text);
  std::string field;
  int n = 0;
  while (std::getline(in, field, ',')) {
    if (n == 4) throw UsageError("--sweep takes four numbers a,b,c,d");
    std::size_t used = 0;
    try {
      v[n] = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != field.size()) throw UsageError("--sweep: not a number: '" + field + "'");
    ++n;
  }
  if (n != 4) throw UsageError("--sweep takes four numbers a,b,c,d");
  if (!(v[3] > 0)) throw UsageError("--sweep: d must be positive");
  return {v[0], v[1], v[2], v[3]};
}

void print_presets() {
  for (const auto& p : sim::presets::list())
    std::printf("  %-24s %s\n", std::string(p.id).c_str(), std::string(p.description).c_str());
}

}  // namespace

int run_simulate(const Args& args) {
  if (args.has("list")) {
    print_presets();
    return 0;
  }
  SimulationRequest req;
  if (args.has("knob") == args.has("params")) throw UsageError("give exactly one of --knob and --params");
  if (auto id = args.get("knob")) {
    const auto knob = sim::presets::knob(*id);
    if (!knob) throw UsageError("unknown knob preset '" + *id + "' (see 'knoblab simulate --list')");
    req.knob = *knob;
    req.knob_name = *id;
  } else {
    const std::string path = args.require("params");
    KnobFile file = read_knob_file(path);
    req.knob = file.knob;
    req.effects = std::move(file.effects);  // a model file's; --effects adds to them
    req.knob_name = path;
  }
  if (auto text = args.get("effects")) {
    try {
      for (model::EffectSpec& e : model::parse_effect_specs(*text)) req.effects.push_back(std::move(e));
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--effects: ") + e.what());
    }
  }
  req.seconds = args.number("seconds", req.seconds);
  req.rate_hz = args.number("rate", req.rate_hz);
  const long long seed = args.integer("seed", 1);
  if (seed < 0) throw UsageError("--seed must not be negative");
  req.seed = static_cast<std::uint64_t>(seed);
  req.mode = args.get("mode").value_or("lab");
  req.tilt_rad = args.number("tilt", 30.0) * std::numbers::pi / 180.0;
  const std::string amp = args.get("amp").value_or("current");
  if (amp != "current" && amp != "voltage") throw UsageError("--amp must be 'current' or 'voltage'");
  req.amp = amp == "current" ? sim::AmpMode::Current : sim::AmpMode::Voltage;
  req.pid.Kp = args.number("kp", req.pid.Kp);
  req.pid.Ki = args.number("ki", req.pid.Ki);
  req.pid.Kd = args.number("kd", req.pid.Kd);
  if (auto s = args.get("sweep")) req.stimulus = parse_sweep(*s);

  Progress progress = Progress::on_stderr(args, "simulate");
  const CancelOnSignal cancel;
  req.hooks = progress.hooks();
  std::optional<store::Store> db;
  if (auto path = args.get("db")) db.emplace(store::Store::open(*path));
  SimulationResult r;
  try {
    r = simulate(req, db ? &*db : nullptr);
  } catch (const CaptureFailed& failed) {
    progress.clear();
    // What was captured up to the fault is kept, marked incomplete, for a
    // look at where it went wrong; the exit status says it failed.
    std::string why = failed.what();
    const SimulationResult& part = failed.partial();
    if (auto out = args.get("out"); out && part.capture.size() >= interchange::kMinRows) {
      interchange::write_csv(part.capture, std::filesystem::path(*out));
      why += ". The " + std::to_string(part.capture.size()) + " samples up to there are in " + *out +
             ", marked incomplete";
    }
    if (part.capture_id)
      why += "; the store holds them as incomplete capture " + std::to_string(*part.capture_id);
    throw std::runtime_error(why);
  }
  progress.clear();
  if (auto out = args.get("out")) interchange::write_csv(r.capture, std::filesystem::path(*out));

  const CaptureSummary s = summarize(r.capture);
  std::printf("knob %s: %zu samples, %.3f s at %.0f Hz\n", req.knob_name.c_str(), s.samples,
              s.duration_s, req.rate_hz);
  std::printf("  position %.1f° … %.1f°, torque %.2f … %.2f mN·m (rms %.2f)\n",
              s.theta_min * 180 / std::numbers::pi, s.theta_max * 180 / std::numbers::pi,
              s.torque_min * 1e3, s.torque_max * 1e3, s.torque_rms * 1e3);
  std::printf("  tracking error rms %.3f°, peak command %.2f V\n",
              r.tracking_rms_rad * 180 / std::numbers::pi, r.max_command_V);
  if (auto out = args.get("out")) std::printf("  wrote %s\n", out->c_str());
  if (r.capture_id) std::printf("  stored as capture %lld in %s\n", static_cast<long long>(*r.capture_id),
                                args.get("db")->c_str());
  return 0;
}

}  // namespace knoblab::cli
