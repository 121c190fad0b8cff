// knoblab convert: an outside recording (MAT v5/v7/v7.3, .npy, .npz, or
// another tool's CSV) to interchange CSV; a vector over one revolution to a
// static map. Only reshaping, unit scaling and a time shift: no resampling
// or filtering (the fit's data preparation handles irregular host time
// stamps).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "cancel.hpp"
#include "commands.hpp"
#include "convert_arrays.hpp"
#include "convert_map.hpp"
#include "progress.hpp"
#include "knoblab/interchange/array_file.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/mapped_csv.hpp"
#include "knoblab/interchange/number_text.hpp"
#include "knoblab/model/filters.hpp"

namespace knoblab::cli {

const CommandSpec kConvertSpec{
    "convert", "IN OUT.csv (--columns NAMES|MAPPING | --map-over-rev) [OPTIONS]",
    "Convert an outside recording to interchange CSV.\n"
    "IN is a MATLAB MAT-file (v5, -v7 or -v7.3), a NumPy .npy or .npz, or another tool's CSV\n"
    "(told apart by content).\n"
    "Arrays: --columns names the channel each matrix row (or column) holds: t, theta,\n"
    "omega, alpha, torque, command, or - to skip one; for a cell array each name takes one\n"
    "row of cells and the cell columns (segments) are joined in order.\n"
    "CSV: --columns maps the file's columns, SOURCE=CHANNEL[:UNIT] each; unnamed columns are\n"
    "ignored. Units: t s|ms|us; theta rad|deg|rev|counts; omega rad/s|deg/s|rev/s|rpm;\n"
    "alpha rad/s^2|deg/s^2|rev/s^2; torque N*m|mN*m|uN*m; command V|mV; or *FACTOR (SI per\n"
    "unit); none means SI. Time is shifted to start at 0; omega and alpha, when not given,\n"
    "are derived from theta. --map-over-rev: a vector of N values over one revolution\n"
    "(position i at 2*pi*i/N) becomes a static map (theta,torque; '# kind: static-map').\n"
    "More in docs/interchange.md. Ctrl-C cancels it before OUT is written (exit status 130);\n"
    "OUT is written whole or not at all.",
    {{"columns", true, "arrays: channel of each row (or column), e.g. t,theta,torque or -,t,theta,torque; "
                       "CSV: SOURCE=CHANNEL[:UNIT],... e.g. time_ms=t:ms,angle=theta:deg,i_A=torque:*0.0551",
      "NAMES|MAPPING"},
     {"var", true, "variable (MAT) or member (.npz) to read, e.g. data (default: the file's only one)", "NAME"},
     {"counts-per-rev", true, "encoder counts per revolution, e.g. 8192: arrays: theta is in counts "
                              "(scale 2*pi/N); CSV: enables the unit counts", "N"},
     {"theta-scale", true, "arrays: rad per unit of theta (also scales omega, alpha), e.g. 0.0174533 "
                           "for degrees; default 1", "X"},
     {"torque-scale", true, "arrays and maps: N*m per unit of torque, e.g. 0.0551 for current in A; "
                            "default 1", "X"},
     {"unwrap", false, "undo position jumps of over half a revolution (arrays: needs --counts-per-rev)"},
     {"segment-time", true, "cell arrays: continuous (default), or restart when each segment's clock "
                            "starts again at 0", "continuous|restart"},
     {"delimiter", true, "CSV: the field delimiter, e.g. ';' (default: the one the header uses)", ",|;|tab"},
     {"map-over-rev", false, "IN holds one value per position over one revolution: write a static map"},
     {"missing", true, "with --map-over-rev: the value that marks a position not measured, e.g. 0 or nan; "
                       "those positions are left out", "X|nan"},
     {"knob", true, "knob name for the '# knob:' line (import files it under this name), e.g. odrive-gimbal"},
     kQuietOption},
    2, 2, true,
    {"knoblab convert slow2/nocomp_0.mat nocomp_0.csv --columns t,theta,torque --counts-per-rev 8192 "
     "--torque-scale 0.0551 --unwrap",
     "knoblab convert log.csv k.csv --columns time_ms=t:ms,angle_deg=theta:deg,torque_mNm=torque:mN*m",
     "knoblab convert coggingmap_0/cogging_measure_final_a_16.npy map.csv --map-over-rev --torque-scale 0.0551 "
     "--missing 0"}};

namespace {

using convert::Channels;
using convert::kAlpha;
using convert::kCommand;
using convert::kOmega;
using convert::kT;
using convert::kTheta;
using convert::kTorque;
using interchange::MatArray;
using interchange::shortest;
using Metadata = std::vector<std::pair<std::string, std::string>>;

// The array to convert: --var, or the file's only one.
MatArray pick_array(const std::string& file, const Args& args) {
  std::vector<MatArray> vars = interchange::read_array_file(file);
  if (auto name = args.get("var")) return interchange::take_array(vars, *name, file);
  if (vars.size() == 1) return std::move(vars[0]);
  std::string names;
  for (const auto& v : vars) names += (names.empty() ? "" : ", ") + v.name + " (" + v.describe() + ")";
  throw UsageError(file + " holds " + std::to_string(vars.size()) + " variables" +
                   (names.empty() ? "" : ": " + names + "; choose one with --var"));
}

// Is IN one of the array files, by its first bytes (or, for a file too
// broken to tell, by its name)?
bool is_array_input(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::string head(32, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (interchange::array_file_kind(head) != interchange::ArrayFileKind::kNone) return true;
  const std::string ext = std::filesystem::path(file).extension().string();
  return !in.is_open() || ext == ".mat" || ext == ".npy" || ext == ".npz";
}

double positive_counts(const Args& args) {
  const double counts = args.number("counts-per-rev", 0.0);
  if (args.has("counts-per-rev") && !(counts > 0)) throw UsageError("--counts-per-rev must be positive");
  return counts;
}

// The time series tail: time shifted to 0 (its offset kept as t0_s after
// the `lead` metadata), derived channels, validated.
interchange::Capture finish_capture(Channels ch, Metadata lead, const Metadata& rest, const std::string& what) {
  const auto& t_raw = ch[kT];
  if (t_raw.size() < interchange::kMinRows)
    throw std::runtime_error(what + " holds " + std::to_string(t_raw.size()) + " samples; at least " +
                             std::to_string(interchange::kMinRows) + " are needed");
  for (std::size_t i = 1; i < t_raw.size(); ++i)
    if (!(t_raw[i] > t_raw[i - 1]))
      throw std::runtime_error(what + ": time does not increase: sample " + std::to_string(i + 1) + " (t = " +
                               shortest(t_raw[i]) + " s) follows t = " + shortest(t_raw[i - 1]) + " s");
  const double t0 = ch[kT][0];
  for (double& x : ch[kT]) x -= t0;  // host epoch stamps would lose precision
  interchange::Capture cap;
  cap.metadata = std::move(lead);
  cap.metadata.emplace_back("t0_s", shortest(t0));
  cap.metadata.insert(cap.metadata.end(), rest.begin(), rest.end());
  cap.t = std::move(ch[kT]);
  cap.theta = std::move(ch[kTheta]);
  cap.torque = std::move(ch[kTorque]);
  cap.has_command = !ch[kCommand].empty();
  cap.command = std::move(ch[kCommand]);
  // Derived as the CSV reader derives a missing column; the writer leaves
  // derived columns out, so the file says what was measured.
  try {
    cap.omega_derived = ch[kOmega].empty();
    cap.omega = cap.omega_derived ? model::derivative(cap.t, cap.theta) : std::move(ch[kOmega]);
    cap.alpha_derived = ch[kAlpha].empty();
    cap.alpha = cap.alpha_derived ? model::derivative(cap.t, cap.omega) : std::move(ch[kAlpha]);
    interchange::validate(cap);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
  return cap;
}

Metadata leading_metadata(const Args& args, const std::string& what) {
  Metadata m;
  if (auto knob = args.get("knob")) m.emplace_back("knob", *knob);
  m.emplace_back("source", what);
  return m;
}

void refuse(const Args& args, std::initializer_list<const char*> options, const std::string& why) {
  for (const char* o : options)
    if (args.has(o)) throw UsageError("--" + std::string(o) + " " + why);
}

int convert_map(const std::string& in, const std::string& out, const Args& args, Progress& progress) {
  refuse(args, {"columns", "segment-time", "unwrap", "theta-scale", "delimiter"},
         "does not apply to --map-over-rev (position i of N values is at 2*pi*i/N)");
  std::optional<double> missing;
  if (auto m = args.get("missing")) missing = m == "nan" || m == "NaN" ? std::nan("") : args.number("missing", 0.0);
  const double torque_scale = args.number("torque-scale", 1.0);
  progress.show("reading " + in);
  const MatArray var = pick_array(in, args);
  throw_if_cancelled();
  const std::string what = std::filesystem::path(in).filename().string() + ":" + var.name;
  convert::MapResult r = convert::map_over_rev(var, what, torque_scale, missing);
  if (const double counts = positive_counts(args); counts > 0 && counts != static_cast<double>(r.positions))
    throw UsageError("--counts-per-rev " + shortest(counts) + ", but " + what + " holds " +
                     std::to_string(r.positions) + " positions over the revolution");
  r.map.metadata = leading_metadata(args, what);
  r.map.metadata.emplace_back("positions_per_rev", std::to_string(r.positions));
  r.map.metadata.emplace_back("torque_scale", shortest(torque_scale));
  if (missing)
    r.map.metadata.emplace_back("missing", std::string(std::isnan(*missing) ? "nan" : shortest(*missing)) + ": " +
                                               std::to_string(r.missing) + " positions not measured, left out");
  throw_if_cancelled();  // the last chance: from here OUT is written whole
  progress.show("writing " + out);
  interchange::write_static_map(r.map, std::filesystem::path(out));
  progress.clear();

  std::printf("converted %s (%s): static map of %zu of %zu positions over one revolution to %s\n", what.c_str(),
              var.describe().c_str(), r.map.size(), r.positions, out.c_str());
  if (!missing) {
    std::size_t zeros = 0;
    for (double q : r.map.torque) zeros += q == 0.0 ? 1 : 0;
    if (zeros * 4 >= r.map.size())
      std::printf("note: %zu of the %zu values are exactly 0; if they mark positions not measured, add --missing 0\n",
                  zeros, r.map.size());
  }
  return 0;
}

int convert_arrays(const std::string& in, const std::string& out, const Args& args, Progress& progress) {
  refuse(args, {"delimiter"}, "is for CSV input; " + in + " is a MAT, .npy or .npz file");
  const std::vector<int> cols = convert::parse_channel_list(args.require("columns"));
  if (args.has("counts-per-rev") && args.has("theta-scale"))
    throw UsageError("give --counts-per-rev or --theta-scale, not both");
  if (args.has("unwrap") && !args.has("counts-per-rev"))
    throw UsageError("--unwrap needs --counts-per-rev (the revolution to unwrap by)");
  const double counts = positive_counts(args);
  const double theta_scale = counts > 0 ? 2 * std::numbers::pi / counts : args.number("theta-scale", 1.0);
  const double torque_scale = args.number("torque-scale", 1.0);
  const std::string segment_time = args.get("segment-time").value_or("continuous");
  if (segment_time != "continuous" && segment_time != "restart")
    throw UsageError("--segment-time must be 'continuous' or 'restart'");

  progress.show("reading " + in);
  const MatArray var = pick_array(in, args);
  throw_if_cancelled();
  const std::string what = std::filesystem::path(in).filename().string() + ":" + var.name;
  if (!var.is_cell() && !var.is_numeric())
    throw std::runtime_error(what + " is " + var.describe() +
                             "; convert reads a real numeric matrix or a cell array of them");
  if (!var.is_cell() && args.has("segment-time"))
    throw UsageError("--segment-time is for cell arrays; " + what + " is " + var.describe());
  Channels ch = var.is_cell() ? convert::from_cells(var, cols, what, segment_time == "restart")
                              : convert::from_matrix(var, cols, what);
  const std::size_t jumps = args.has("unwrap") ? convert::unwrap(ch[kTheta], counts) : 0;
  for (auto c : {kTheta, kOmega, kAlpha})
    for (double& x : ch[c]) x *= theta_scale;
  for (double& x : ch[kTorque]) x *= torque_scale;

  Metadata meta;
  if (counts > 0) meta.emplace_back("counts_per_rev", shortest(counts));
  meta.emplace_back("theta_scale", shortest(theta_scale));
  meta.emplace_back("torque_scale", shortest(torque_scale));
  if (args.has("unwrap")) meta.emplace_back("unwrapped_jumps", std::to_string(jumps));
  if (var.is_cell())
    meta.emplace_back("segments", std::to_string(var.cols()) + (segment_time == "restart"
                                      ? ", clock restarting; each placed one median interval after the last"
                                      : ", joined"));
  progress.show("deriving the capture");
  const interchange::Capture cap = finish_capture(std::move(ch), leading_metadata(args, what), meta, what);
  throw_if_cancelled();  // the last chance: from here OUT is written whole
  progress.show("writing " + out);
  interchange::write_csv(cap, std::filesystem::path(out));
  progress.clear();

  std::printf("converted %s (%s): %zu samples over %.3f s to %s", what.c_str(), var.describe().c_str(),
              cap.size(), cap.t.back(), out.c_str());
  if (args.has("unwrap")) std::printf("; %zu position jump(s) unwrapped", jumps);
  std::printf("\n");
  return 0;
}

int convert_csv(const std::string& in, const std::string& out, const Args& args, Progress& progress) {
  refuse(args, {"theta-scale", "torque-scale"}, "is for arrays; for a CSV give the unit in --columns, "
                                                 "e.g. angle=theta:deg or current_A=torque:*0.0551");
  refuse(args, {"var", "segment-time"}, "is for MAT, .npy and .npz files; " + in + " is read as a CSV");
  char delimiter = 0;
  if (auto d = args.get("delimiter")) {
    if (*d == "," || *d == ";") delimiter = (*d)[0];
    else if (*d == "tab" || *d == "\t") delimiter = '\t';
    else throw UsageError("--delimiter must be ',', ';' or tab");
  }
  std::vector<interchange::ColumnMapping> mapping;
  try {
    mapping = interchange::parse_column_mapping(args.require("columns"), positive_counts(args));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  progress.show("reading " + in);
  interchange::MappedCsv csv = interchange::read_mapped_csv(in, mapping, delimiter);
  throw_if_cancelled();
  const std::string what = std::filesystem::path(in).filename().string();
  // In SI already: a wrap is a jump of more than half of 2*pi.
  const std::size_t jumps = args.has("unwrap") ? convert::unwrap(csv.channels[kTheta], 2 * std::numbers::pi) : 0;

  Metadata meta;
  meta.emplace_back("columns", interchange::mapping_text(mapping));
  if (args.has("unwrap")) meta.emplace_back("unwrapped_jumps", std::to_string(jumps));
  std::string ignored;
  for (const auto& n : csv.ignored) ignored += (ignored.empty() ? "" : ", ") + n;
  if (!ignored.empty()) meta.emplace_back("ignored_columns", ignored);
  Channels ch;
  for (std::size_t c = 0; c < ch.size(); ++c) ch[c] = std::move(csv.channels[c]);
  progress.show("deriving the capture");
  const interchange::Capture cap = finish_capture(std::move(ch), leading_metadata(args, what), meta, what);
  throw_if_cancelled();  // the last chance: from here OUT is written whole
  progress.show("writing " + out);
  interchange::write_csv(cap, std::filesystem::path(out));
  progress.clear();

  std::printf("converted %s (CSV, delimiter %s): %zu samples over %.3f s to %s", what.c_str(),
              csv.delimiter == '\t' ? "tab" : std::string(1, csv.delimiter).c_str(), cap.size(), cap.t.back(),
              out.c_str());
  if (!ignored.empty()) std::printf("; columns ignored: %s", ignored.c_str());
  if (args.has("unwrap")) std::printf("; %zu position jump(s) unwrapped", jumps);
  std::printf("\n");
  return 0;
}

}  // namespace

int run_convert(const Args& args) {
  const std::string in = args.positionals().at(0), out = args.positionals().at(1);
  if (args.has("missing") && !args.has("map-over-rev")) throw UsageError("--missing is for --map-over-rev");
  if (!args.has("map-over-rev") && !args.has("columns"))
    throw UsageError("'convert' needs --columns (or --map-over-rev for a map)");
  Progress progress = Progress::on_stderr(args, "convert");
  const CancelOnSignal cancel;
  if (args.has("map-over-rev")) return convert_map(in, out, args, progress);
  return is_array_input(in) ? convert_arrays(in, out, args, progress) : convert_csv(in, out, args, progress);
}

}  // namespace knoblab::cli
