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
#include "table_output.hpp"

namespace knoblab::cli {

namespace {

// A static map: its points and the strongest harmonics of torque over the
// revolution. --json: one object with the harmonics as an array; --csv: the
// harmonics, one row each.
int inspect_map(const interchange::StaticMap& map, const std::string& name, const Args& args) {
  const MapSummary s = summarize_map(map);
  Table harmonics{{"cycles_per_rev", "amplitude_Nm", "power"}, {}};
  for (const auto& h : s.harmonics) harmonics.rows.push_back({h.cycles_per_rev, h.amplitude, h.power});
  if (args.has("json")) {
    nlohmann::json j = {{"kind", "static-map"},        {"points", s.points},
                        {"theta_min_rad", s.theta_min}, {"theta_max_rad", s.theta_max},
                        {"spacing_rad", s.spacing},     {"torque_min_Nm", s.torque_min},
                        {"torque_max_Nm", s.torque_max}, {"torque_mean_Nm", s.torque_mean},
                        {"torque_rms_Nm", s.torque_rms}, {"harmonics", nlohmann::json::array()}};
    for (std::size_t i = 0; i < harmonics.rows.size(); ++i) j["harmonics"].push_back(row_object(harmonics, i));
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  if (print_table_if_asked(args, harmonics)) return 0;
  const double deg = 180.0 / std::numbers::pi;
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
    "inspect", "(FILE.csv | --capture ID --db FILE.sqlite) [--json | --csv]",
    "Summarise a recording: its length, rate, ranges and detents.\n"
    "The detents are the strongest position-periodic torque, as cycles per revolution\n"
    "from the torque-versus-position spectrum (text in degrees and mN·m, JSON and CSV in SI);\n"
    "the loop's flags (amplifier, fault, e-stop, torque limit) and an incomplete\n"
    "capture's end reason when the file has them. A static map ('# kind: static-map', from\n"
    "convert --map-over-rev): its points and the strongest whole-number harmonics of torque\n"
    "over the revolution (--csv: the harmonics, one row each).",
    {{"capture", true, "capture id in the store (instead of FILE.csv)"},
     {"db", true, "sqlite store"},
     {"json", false, "print the summary as JSON (SI units)"},
     {"csv", false, "print the summary as one CSV row under a header (SI units)"}},
    0, 1, true,
    {"knoblab inspect knob.csv", "knoblab inspect --capture 1 --db lab.sqlite --json",
     "knoblab inspect cogging_map.csv --json"}};

int run_inspect(const Args& args) {
  interchange::Capture capture;
  std::string name;
  if (args.has("json") && args.has("csv")) throw UsageError("give --json or --csv, not both");
  if (const auto file = args.input()) {
    if (args.has("capture")) throw UsageError("give a FILE or --capture, not both");
    name = *file;
    interchange::Recording r = interchange::read_recording(name);
    if (const auto* map = std::get_if<interchange::StaticMap>(&r)) return inspect_map(*map, name, args);
    capture = std::move(std::get<interchange::Capture>(r));
  } else {
    const std::string id = args.require("capture");
    const long long capture_id = parse_id("--capture", id);
    store::Store db = open_store_to_read(args.require("db"));
    capture = db.load_samples(capture_id);
    name = "capture " + id;
  }
  const CaptureSummary s = summarize(capture);
  const double deg = 180.0 / std::numbers::pi;
  Table table{{"samples", "duration_s", "mean_rate_hz", "theta_min_rad", "theta_max_rad",
                "omega_max_abs_rad_s", "torque_min_Nm", "torque_max_Nm", "torque_rms_Nm",
                "detent_cycles_per_rev", "detent_amplitude_Nm", "detent_power"},
               {{s.samples, s.duration_s, s.mean_rate_hz, s.theta_min, s.theta_max, s.omega_max_abs,
                 s.torque_min, s.torque_max, s.torque_rms,
                 s.detent_cycles_per_rev ? nlohmann::json(*s.detent_cycles_per_rev) : nlohmann::json(),
                 s.detent_cycles_per_rev ? nlohmann::json(s.detent_amplitude) : nlohmann::json(),
                 s.detent_cycles_per_rev ? nlohmann::json(s.detent_power) : nlohmann::json()}}};
  if (args.has("json")) {
    // One object, not a one-row array: the summary of one recording.
    std::printf("%s\n", row_object(table, 0).dump().c_str());
    return 0;
  }
  if (print_table_if_asked(args, table)) return 0;
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
