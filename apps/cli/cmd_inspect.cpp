// knoblab inspect: a recording at a glance, and where its detents are.
#include <cstdio>
#include <numbers>
#include <optional>

#include "commands.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/sample.hpp"
#include "knoblab/store/store.hpp"
#include "map_summary.hpp"
#include "store_open.hpp"
#include "summary.hpp"

namespace knoblab::cli {

namespace {

int inspect_map(const interchange::StaticMap& map, const std::string& name, bool json) {
  const MapSummary s = summarize_map(map);
  const double deg = 180.0 / std::numbers::pi;
  if (json) {
    std::printf("{\"kind\": \"static-map\", \"points\": %zu, \"theta_min_rad\": %.9g, \"theta_max_rad\": %.9g, "
                "\"spacing_rad\": %.9g, \"torque_min_Nm\": %.9g, \"torque_max_Nm\": %.9g, \"torque_mean_Nm\": %.9g, "
                "\"torque_rms_Nm\": %.9g, \"harmonics\": [",
                s.points, s.theta_min, s.theta_max, s.spacing, s.torque_min, s.torque_max, s.torque_mean, s.torque_rms);
    for (std::size_t i = 0; i < s.harmonics.size(); ++i)
      std::printf("%s{\"cycles_per_rev\": %d, \"amplitude_Nm\": %.9g, \"power\": %.6g}", i ? ", " : "",
                  s.harmonics[i].cycles_per_rev, s.harmonics[i].amplitude, s.harmonics[i].power);
    std::printf("]}\n");
    return 0;
  }
  std::printf("%s: static map of %zu positions, %.2f° … %.2f° (median spacing %.3f°)\n", name.c_str(), s.points,
              s.theta_min * deg, s.theta_max * deg, s.spacing * deg);
  std::printf("  torque     %.3f … %.3f mN·m, mean %.3f mN·m, rms %.3f mN·m\n", s.torque_min * 1e3, s.torque_max * 1e3,
              s.torque_mean * 1e3, s.torque_rms * 1e3);
  std::printf("  spectrum   strongest harmonics (cycles/rev: amplitude, share of torque variance):\n");
  for (const auto& h : s.harmonics)
    std::printf("             %4d: %8.3f mN·m  %3.0f%%\n", h.cycles_per_rev, h.amplitude * 1e3, h.power * 100);
  return 0;
}

}  // namespace

const CommandSpec kInspectSpec{
    "inspect", "FILE.csv | --capture ID --db FILE [--json]",
    "Summarise a recording: length, rate, ranges, and the strongest position-periodic\n"
    "torque (detents) as cycles per revolution from the torque-versus-position spectrum;\n"
    "the loop's flags (amplifier, fault, e-stop, torque limit) and an incomplete\n"
    "capture's end reason when the file has them. A static map ('# kind: static-map', from\n"
    "convert --map-over-rev): its points and the strongest whole-number harmonics of\n"
    "torque over the revolution.\n"
    "Example: knoblab inspect map.csv --json",
    {{"capture", true, "capture id in the store", "ID"},
     {"db", true, "sqlite store", "FILE"},
     {"json", false, "print the summary as JSON (SI units)"}},
    0, 1};

int run_inspect(const Args& args) {
  interchange::Capture capture;
  std::string name;
  if (!args.positionals().empty()) {
    if (args.has("capture")) throw UsageError("give a FILE or --capture, not both");
    name = args.positionals()[0];
    interchange::Recording r = interchange::read_recording(name);
    if (const auto* map = std::get_if<interchange::StaticMap>(&r)) return inspect_map(*map, name, args.has("json"));
    capture = std::move(std::get<interchange::Capture>(r));
  } else {
    const std::string id = args.require("capture");
    store::Store db = open_store_to_read(args.require("db"));
    capture = db.load_samples(std::stoll(id));
    name = "capture " + id;
  }
  const CaptureSummary s = summarize(capture);
  const double deg = 180.0 / std::numbers::pi;
  if (args.has("json")) {
    std::printf("{\"samples\": %zu, \"duration_s\": %.9g, \"mean_rate_hz\": %.9g, "
                "\"theta_min_rad\": %.9g, \"theta_max_rad\": %.9g, \"torque_min_Nm\": %.9g, "
                "\"torque_max_Nm\": %.9g, \"torque_rms_Nm\": %.9g, \"detent_cycles_per_rev\": ",
                s.samples, s.duration_s, s.mean_rate_hz, s.theta_min, s.theta_max, s.torque_min,
                s.torque_max, s.torque_rms);
    if (s.detent_cycles_per_rev)
      std::printf("%.9g, \"detent_amplitude_Nm\": %.9g, \"detent_power\": %.6g}\n",
                  *s.detent_cycles_per_rev, s.detent_amplitude, s.detent_power);
    else
      std::printf("null}\n");
    return 0;
  }
  std::printf("%s: %zu samples over %.3f s (mean rate %.1f Hz)\n", name.c_str(), s.samples,
              s.duration_s, s.mean_rate_hz);
  std::printf("  position   %.2f° … %.2f°\n", s.theta_min * deg, s.theta_max * deg);
  std::printf("  velocity   up to %.2f °/s\n", s.omega_max_abs * deg);
  std::printf("  torque     %.3f … %.3f mN·m, rms %.3f mN·m\n", s.torque_min * 1e3,
              s.torque_max * 1e3, s.torque_rms * 1e3);
  if (s.detent_cycles_per_rev)
    std::printf("  spectrum   peak at %.2f cycles/rev (period %.2f°), amplitude %.3f mN·m, "
                "explains %.0f%% of torque variance\n",
                *s.detent_cycles_per_rev, 360.0 / *s.detent_cycles_per_rev, s.detent_amplitude * 1e3,
                s.detent_power * 100);
  else
    std::printf("  spectrum   knob travelled less than one period of 64 cycles/rev: none\n");
  if (!capture.flags.empty()) {
    // What the loop did, so a cut capture shows in the summary too.
    std::size_t amp = 0, fault = 0, estop = 0, limited = 0;
    for (std::uint32_t f : capture.flags) {
      amp += (f & interchange::kAmpEnabled) ? 1 : 0;
      fault += (f & interchange::kFaultLatched) ? 1 : 0;
      estop += (f & interchange::kEstopActive) ? 1 : 0;
      limited += (f & interchange::kTorqueLimited) ? 1 : 0;
    }
    std::printf("  flags      amplifier on %zu, fault latched %zu, e-stop %zu, torque limited %zu "
                "(a fit leaves the last three out)\n", amp, fault, estop, limited);
  }
  if (const std::string* status = capture.find_metadata("status"); status && *status != "complete") {
    const std::string* why = capture.find_metadata("end_reason");
    std::printf("  status     %s%s%s\n", status->c_str(), why ? ": " : "", why ? why->c_str() : "");
  }
  return 0;
}

}  // namespace knoblab::cli
