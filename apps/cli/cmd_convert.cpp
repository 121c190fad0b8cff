// knoblab convert: an outside recording in a MATLAB MAT-file to interchange CSV.
// Only reshaping, unit scaling and a time shift: no resampling or filtering
// (the fit's data preparation handles irregular host time stamps).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include "commands.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/interchange/mat5.hpp"
#include "knoblab/interchange/number_text.hpp"
#include "knoblab/model/filters.hpp"

namespace knoblab::cli {

const CommandSpec kConvertSpec{
    "convert", "IN.mat OUT.csv --columns NAMES [OPTIONS]",
    "Convert an outside recording to interchange CSV.\n"
    "The recording is a MATLAB MAT-file (v5, -v7).\n"
    "--columns names the channel each matrix row (or column) holds: t, theta, omega, alpha,\n"
    "torque, command, or - to skip one. For a cell array each name takes one row of cells,\n"
    "and the cell columns (segments) are joined in order. Time is shifted to start at 0;\n"
    "omega and alpha, when not given, are derived from theta. Example (docs/interchange.md):\n"
    "  knoblab convert slow2/nocomp_0.mat nocomp_0.csv --columns t,theta,torque \\\n"
    "      --counts-per-rev 8192 --torque-scale 0.0551 --unwrap --knob odrive-gimbal",
    {{"columns", true, "channel of each row (or column), e.g. t,theta,torque or -,t,theta,torque"},
     {"var", true, "variable to read (default: the file's only variable)"},
     {"counts-per-rev", true, "theta is in encoder counts, N per revolution (scale 2*pi/N)"},
     {"theta-scale", true, "or: rad per unit of theta (also scales omega, alpha); default 1"},
     {"torque-scale", true, "N*m per unit of torque, e.g. 0.0551 for current in A; default 1"},
     {"unwrap", false, "with --counts-per-rev: undo position jumps of over half a revolution"},
     {"segment-time", true, "cell arrays: continuous (default), or restart when each segment's "
                            "clock starts again at 0"},
     {"knob", true, "knob name for the '# knob:' line (import files it under this name)"}},
    2, 2, true,
    {"knoblab convert slow2/nocomp_0.mat nocomp_0.csv --columns t,theta,torque --counts-per-rev 8192 "
     "--torque-scale 0.0551 --unwrap"}};

namespace {

using interchange::MatArray;
using interchange::shortest;
enum Channel : std::size_t { kT, kTheta, kOmega, kAlpha, kTorque, kCommand, kChannelCount };
constexpr int kSkip = -1;

// One entry per --columns name: the channel's index, or kSkip for '-'.
std::vector<int> parse_columns(const std::string& text) {
  std::vector<int> cols;
  std::array<bool, kChannelCount> seen{};
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    std::string name = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    if (name == "-") {
      cols.push_back(kSkip);
    } else {
      const auto it = std::find(interchange::kChannelNames.begin(), interchange::kChannelNames.end(), name);
      if (it == interchange::kChannelNames.end())
        throw UsageError("--columns: unknown channel '" + name +
                         "' (names: t, theta, omega, alpha, torque, command, or - to skip)");
      const auto ch = static_cast<std::size_t>(it - interchange::kChannelNames.begin());
      if (seen[ch]) throw UsageError("--columns: '" + name + "' given twice");
      seen[ch] = true;
      cols.push_back(static_cast<int>(ch));
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (!seen[kT] || !seen[kTheta] || !seen[kTorque])
    throw UsageError("--columns must name t, theta and torque");
  return cols;
}

using Channels = std::array<std::vector<double>, kChannelCount>;  // empty = not in the file

// A numeric matrix: its rows are the channels if there are as many rows as
// names, else its columns.
Channels from_matrix(const MatArray& a, const std::vector<int>& cols, const std::string& what) {
  const std::size_t n = cols.size();
  if (a.dims.size() != 2) throw std::runtime_error(what + " is " + a.describe() + "; expected a 2-D matrix");
  const bool by_rows = a.rows() == n;
  if (!by_rows && a.cols() != n)
    throw std::runtime_error(what + " is " + a.describe() + ": neither its rows nor its columns match the " +
                             std::to_string(n) + " names in --columns");
  const std::size_t samples = by_rows ? a.cols() : a.rows();
  Channels out;
  for (std::size_t k = 0; k < n; ++k) {
    if (cols[k] == kSkip) continue;
    auto& v = out[static_cast<std::size_t>(cols[k])];
    v.resize(samples);
    for (std::size_t i = 0; i < samples; ++i) v[i] = by_rows ? a.at(k, i) : a.at(i, k);
  }
  return out;
}

// Median spacing of time stamps within segments: the assumed pause between
// segments whose clocks restart.
double median_interval(const MatArray& a, std::size_t t_row) {
  std::vector<double> dt;
  for (std::size_t j = 0; j < a.cols(); ++j) {
    const auto& t = a.cell(t_row, j).values;
    for (std::size_t i = 1; i < t.size(); ++i) dt.push_back(t[i] - t[i - 1]);
  }
  if (dt.empty()) throw std::runtime_error("no segment has two samples to space the segments by");
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

// A cell array: row k of cells holds channel k, each cell column is one
// segment; segments are appended in order.
Channels from_cells(const MatArray& a, const std::vector<int>& cols, const std::string& what, bool restart) {
  const std::size_t n = cols.size();
  if (a.dims.size() != 2 || a.rows() != n)
    throw std::runtime_error(what + " is " + a.describe() + ": --columns names " + std::to_string(n) +
                             " rows, one per row of cells");
  const auto t_row = static_cast<std::size_t>(std::find(cols.begin(), cols.end(), kT) - cols.begin());
  const double pause = restart ? median_interval(a, t_row) : 0.0;
  Channels out;
  std::vector<double>& t = out[kT];
  for (std::size_t j = 0; j < a.cols(); ++j) {
    const std::string seg = "segment " + std::to_string(j + 1) + " (cell column " + std::to_string(j + 1) + ")";
    std::size_t len = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (cols[k] == kSkip) continue;  // whatever a skipped row holds (e.g. a setpoint) is ignored
      const MatArray& c = a.cell(k, j);
      if (!c.is_numeric())
        throw std::runtime_error(what + ": " + seg + ", row " + std::to_string(k + 1) + ": expected numbers, found " +
                                 c.describe());
      if (k != t_row && c.numel() != a.cell(t_row, j).numel())
        throw std::runtime_error(what + ": " + seg + ": row " + std::to_string(k + 1) + " has " +
                                 std::to_string(c.numel()) + " values, the t row " + std::to_string(t_row + 1) +
                                 " has " + std::to_string(a.cell(t_row, j).numel()));
      len = c.numel();
    }
    if (len == 0) continue;
    const auto& seg_t = a.cell(t_row, j).values;
    double offset = 0.0;
    std::size_t first = 0;
    if (!t.empty() && restart) {
      offset = t.back() + pause;  // the segment's clock zero, one median interval after the last sample
    } else if (!t.empty() && seg_t[0] == t.back()) {
      first = 1;  // the boundary sample recorded twice
    } else if (!t.empty() && seg_t[0] < t.back()) {
      throw std::runtime_error(what + ": " + seg + " starts at t = " + shortest(seg_t[0]) +
                               " s, before the previous segment ends (t = " + shortest(t.back()) +
                               " s); if each segment's clock starts again, use --segment-time restart");
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (cols[k] == kSkip) continue;
      const auto& v = a.cell(k, j).values;
      auto& dst = out[static_cast<std::size_t>(cols[k])];
      for (std::size_t i = first; i < v.size(); ++i) dst.push_back(k == t_row ? v[i] + offset : v[i]);
    }
  }
  return out;
}

// Adds or subtracts whole periods where consecutive values jump by more than
// half of one, so a position that wraps (e.g. modulo 8192 counts) is continuous.
std::size_t unwrap(std::vector<double>& x, double period) {
  std::size_t jumps = 0;
  double shift = 0.0, prev = x.empty() ? 0.0 : x[0];
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double raw = x[i];
    const double turns = std::round((raw - prev) / period);
    if (turns != 0.0) {
      shift -= turns * period;
      ++jumps;
    }
    prev = raw;
    x[i] = raw + shift;
  }
  return jumps;
}

// The variable to convert: --var, or the file's only variable.
MatArray pick_variable(const std::string& file, const Args& args) {
  if (auto name = args.get("var")) return interchange::read_mat_variable(file, *name);
  std::vector<MatArray> vars = interchange::read_mat(file);
  if (vars.size() == 1) return std::move(vars[0]);
  std::string names;
  for (const auto& v : vars) names += (names.empty() ? "" : ", ") + v.name + " (" + v.describe() + ")";
  throw UsageError(file + " holds " + std::to_string(vars.size()) + " variables" +
                   (names.empty() ? "" : ": " + names + "; choose one with --var"));
}

}  // namespace

int run_convert(const Args& args) {
  const std::string in = args.positionals().at(0), out = args.positionals().at(1);
  const std::vector<int> cols = parse_columns(args.require("columns"));
  if (args.has("counts-per-rev") && args.has("theta-scale"))
    throw UsageError("give --counts-per-rev or --theta-scale, not both");
  if (args.has("unwrap") && !args.has("counts-per-rev"))
    throw UsageError("--unwrap needs --counts-per-rev (the revolution to unwrap by)");
  const double counts = args.number("counts-per-rev", 0.0);
  if (args.has("counts-per-rev") && !(counts > 0)) throw UsageError("--counts-per-rev must be positive");
  const double theta_scale = counts > 0 ? 2 * std::numbers::pi / counts : args.number("theta-scale", 1.0);
  const double torque_scale = args.number("torque-scale", 1.0);
  const std::string segment_time = args.get("segment-time").value_or("continuous");
  if (segment_time != "continuous" && segment_time != "restart")
    throw UsageError("--segment-time must be 'continuous' or 'restart'");

  const MatArray var = pick_variable(in, args);
  const std::string what = std::filesystem::path(in).filename().string() + ":" + var.name;
  if (!var.is_cell() && !var.is_numeric())
    throw std::runtime_error(what + " is " + var.describe() +
                             "; convert reads a real numeric matrix or a cell array of them");
  if (!var.is_cell() && args.has("segment-time"))
    throw UsageError("--segment-time is for cell arrays; " + what + " is " + var.describe());
  Channels ch = var.is_cell() ? from_cells(var, cols, what, segment_time == "restart") : from_matrix(var, cols, what);
  if (ch[kT].size() < interchange::kMinRows)
    throw std::runtime_error(what + " holds " + std::to_string(ch[kT].size()) + " samples; at least " +
                             std::to_string(interchange::kMinRows) + " are needed");

  const auto& t_raw = ch[kT];
  for (std::size_t i = 1; i < t_raw.size(); ++i)
    if (!(t_raw[i] > t_raw[i - 1]))
      throw std::runtime_error(what + ": time does not increase: sample " + std::to_string(i + 1) + " (t = " +
                               shortest(t_raw[i]) + " s) follows t = " + shortest(t_raw[i - 1]) + " s");

  const std::size_t jumps = args.has("unwrap") ? unwrap(ch[kTheta], counts) : 0;
  const double t0 = ch[kT][0];
  for (double& x : ch[kT]) x -= t0;  // host epoch stamps would lose precision
  for (auto c : {kTheta, kOmega, kAlpha})
    for (double& x : ch[c]) x *= theta_scale;
  for (double& x : ch[kTorque]) x *= torque_scale;

  interchange::Capture cap;
  if (auto knob = args.get("knob")) cap.metadata.emplace_back("knob", *knob);
  cap.metadata.emplace_back("source", what);
  cap.metadata.emplace_back("t0_s", shortest(t0));
  if (counts > 0) cap.metadata.emplace_back("counts_per_rev", shortest(counts));
  cap.metadata.emplace_back("theta_scale", shortest(theta_scale));
  cap.metadata.emplace_back("torque_scale", shortest(torque_scale));
  if (args.has("unwrap")) cap.metadata.emplace_back("unwrapped_jumps", std::to_string(jumps));
  if (var.is_cell())
    cap.metadata.emplace_back("segments", std::to_string(var.cols()) + (segment_time == "restart"
                                              ? ", clock restarting; each placed one median interval after the last"
                                              : ", joined"));
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
  interchange::write_csv(cap, std::filesystem::path(out));

  std::printf("converted %s (%s): %zu samples over %.3f s to %s", what.c_str(), var.describe().c_str(),
              cap.size(), cap.t.back(), out.c_str());
  if (args.has("unwrap")) std::printf("; %zu position jump(s) unwrapped", jumps);
  std::printf("\n");
  return 0;
}

}  // namespace knoblab::cli
