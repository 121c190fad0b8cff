// knoblab-fit-bench: knoblab's Eq. 6 fit against scipy.optimize.least_squares
// on the same data and model (the fit's speed claim).
//
//   knoblab-fit-bench [--samples N] [--seed S] [--repeats R] [--json FILE]
//                     [--csv FILE] [--no-peer] [--breakdown]
//
// 1. The thesis' validation data (Eq. 8–11, fit::make_validation_data):
//    N samples at 5 kHz, written as CSV (t,theta,omega,alpha,torque, %.17g).
// 2. fit::fit_knob on it in-process, R times, from no starting values (it
//    searches the detent period itself); median and minimum wall time.
// 3. The peer, `python3 bench/fit/scipy_peer.py data.csv`, fits the same model
//    with least_squares from the TRUE parameters (its most favourable start)
//    in several variants and prints one JSON line (see the script).
// 4. Side by side: times, the ratio scipy/knoblab (against scipy's fastest
//    variant), parameter errors against the truth and the RMS residual over
//    every sample, and a verdict. A benchmark reports, it does not gate: the
//    exit status is 0 whatever the ratio, 1 on errors (bad arguments, a fit
//    that throws, a missing or failing peer).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/validation_data.hpp"

#ifndef KNOBLAB_FIT_BENCH_DIR
#error "KNOBLAB_FIT_BENCH_DIR (the benchmark's source folder) must be defined"
#endif

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
namespace fit = knoblab::fit;

constexpr double kTargetRatio = 10.0;

struct Options {
  std::size_t samples = 150000;
  std::uint64_t seed = 1;
  int repeats = 5;
  std::string json_path;
  std::string csv_path;  // empty: a temporary file, removed afterwards
  bool peer = true;
  bool breakdown = false;
};

void usage(std::ostream& os) {
  os << "usage: knoblab-fit-bench [--samples N] [--seed S] [--repeats R] [--json FILE]\n"
        "                         [--csv FILE] [--no-peer] [--breakdown]\n"
        "  --samples N   validation samples at 5 kHz (default 150000 = 30 s)\n"
        "  --seed S      noise seed (default 1)\n"
        "  --repeats R   timed knoblab fits (default 5; the peer times each variant\n"
        "                max(3, R) times)\n"
        "  --json FILE   write the figures as JSON\n"
        "  --csv FILE    keep the data CSV there (default: a temporary file)\n"
        "  --no-peer     time knoblab only\n"
        "  --breakdown   also time knoblab's phases (start search, solve, rest)\n";
}

std::uint64_t parse_count(const std::string& flag, const std::string& v) {
  std::size_t used = 0;
  unsigned long long x = 0;
  try {
    x = std::stoull(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || v.empty() || v[0] == '-') {
    throw std::invalid_argument(flag + " needs a non-negative integer, got '" + v + "'");
  }
  return x;
}

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--samples") {
      o.samples = parse_count(a, value());
    } else if (a == "--seed") {
      o.seed = parse_count(a, value());
    } else if (a == "--repeats") {
      const std::uint64_t r = parse_count(a, value());
      if (r < 1 || r > 1000) throw std::invalid_argument("--repeats must be 1 … 1000");
      o.repeats = static_cast<int>(r);
    } else if (a == "--json") {
      o.json_path = value();
    } else if (a == "--csv") {
      o.csv_path = value();
    } else if (a == "--no-peer") {
      o.peer = false;
    } else if (a == "--breakdown") {
      o.breakdown = true;
    } else if (a == "-h" || a == "--help") {
      usage(std::cout);
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown argument '" + a + "'");
    }
  }
  if (o.samples < 1000) throw std::invalid_argument("--samples must be at least 1000");
  return o;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Timing {
  std::vector<double> wall, cpu;
  double median_s() const { return median(wall); }
  double min_s() const { return *std::min_element(wall.begin(), wall.end()); }
  double cpu_median_s() const { return median(cpu); }
};

// Times `fn` `repeats` times; returns the last result.
template <typename F>
auto timed(int repeats, Timing& t, F&& fn) {
  std::optional<decltype(fn())> last;
  for (int k = 0; k < repeats; ++k) {
    const double c0 = cpu_now();
    const auto t0 = std::chrono::steady_clock::now();
    last.emplace(fn());
    t.wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    t.cpu.push_back(cpu_now() - c0);
  }
  return std::move(*last);
}

void write_csv(const fit::FitData& d, const fs::path& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path.string());
  std::fputs("t,theta,omega,alpha,torque\n", f);
  for (std::size_t i = 0; i < d.size(); ++i) {
    std::fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", d.t[i], d.theta[i], d.omega[i],
                 d.alpha[i], d.torque[i]);
  }
  if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + path.string());
}

// How close a parameter vector is to the truth, and how well it fits.
struct Errors {
  std::vector<double> rel_pct;  // 100·(p − truth)/|truth|
  double max_abs_rel_pct = 0.0;
  double rms_rel_pct = 0.0;
  double rmse_Nm = 0.0;  // RMS residual over every sample
};

Errors errors_of(const std::vector<double>& p, const std::vector<double>& truth,
                 const fit::FitData& d) {
  Errors e;
  double ss = 0.0;
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const double r = 100.0 * (p[k] - truth[k]) / std::abs(truth[k]);
    e.rel_pct.push_back(r);
    e.max_abs_rel_pct = std::max(e.max_abs_rel_pct, std::abs(r));
    ss += r * r;
  }
  e.rms_rel_pct = std::sqrt(ss / static_cast<double>(truth.size()));
  const auto m = knoblab::model::ThesisModel<double>::from_params(p.data());
  double rss = 0.0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double r = d.torque[i] - m.torque(d.kinematics(i));
    rss += r * r;
  }
  e.rmse_Nm = std::sqrt(rss / static_cast<double>(d.size()));
  return e;
}

json errors_json(const Errors& e) {
  return {{"rel_err_pct", e.rel_pct},
          {"max_abs_rel_err_pct", e.max_abs_rel_pct},
          {"rms_rel_err_pct", e.rms_rel_pct},
          {"rmse_all_Nm", e.rmse_Nm}};
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

// Runs the peer and returns its JSON line. Throws when it cannot run or fails.
json run_peer(const fs::path& csv, int repeats) {
  const fs::path script = fs::path(KNOBLAB_FIT_BENCH_DIR) / "scipy_peer.py";
  if (!fs::exists(script)) throw std::runtime_error("peer missing: " + script.string());
  const std::string cmd = "python3 " + shell_quote(script.string()) + " " +
                          shell_quote(csv.string()) + " --repeats " + std::to_string(repeats);
  std::FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("cannot start the peer: " + cmd);
  std::string out;
  char buf[4096];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, got);
  const int status = pclose(p);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("the peer failed (" + cmd + "), exit status " +
                             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1));
  }
  // The last non-empty line is the JSON.
  std::istringstream lines(out);
  std::string line, last;
  while (std::getline(lines, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  json j = json::parse(last, nullptr, false);
  if (j.is_discarded() || !j.contains("variants") || !j.contains("best") || j["best"].is_null()) {
    throw std::runtime_error("the peer printed no usable result: " + last);
  }
  for (const json& v : j["variants"]) {
    if (v.at("params").size() != 8) throw std::runtime_error("the peer's params are not 8 values");
  }
  return j;
}

// Pads to `width` columns (code points, so "N·m" counts as 3).
std::string pad(std::string s, std::size_t width) {
  std::size_t cols = 0;
  for (unsigned char c : s) cols += (c & 0xC0) != 0x80 ? 1 : 0;
  if (cols < width) s.append(width - cols, ' ');
  return s;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// "equal" when the two fits agree to well inside the statistics (every
// parameter within 1 % of knoblab's standard error of each other, RMS
// residuals within 1e-6 relative): both found the same least-squares optimum.
// Otherwise each figure is better or worse on its own, and a fit worse in
// either is "worse".
struct Verdict {
  std::string params, residual, overall;
};

Verdict compare(const std::vector<double>& pk, const std::vector<double>& ps,
                const std::vector<double>& se, const Errors& ek, const Errors& es) {
  Verdict v;
  bool same = true;
  for (std::size_t k = 0; k < pk.size(); ++k) {
    const double tol = std::max(0.01 * se[k], 1e-12 * std::abs(ps[k]));
    if (std::abs(pk[k] - ps[k]) > tol) same = false;
  }
  v.params = same ? "equal" : (ek.rms_rel_pct < es.rms_rel_pct ? "better" : "worse");
  const double dr = (ek.rmse_Nm - es.rmse_Nm) / es.rmse_Nm;
  v.residual = std::abs(dr) <= 1e-6 ? "equal" : (dr < 0 ? "better" : "worse");
  if (v.params == "worse" || v.residual == "worse") {
    v.overall = "worse";
  } else if (v.params == "better" || v.residual == "better") {
    v.overall = "better";
  } else {
    v.overall = "equal";
  }
  return v;
}

// --breakdown: where fit_knob's time goes, from the phase clock it keeps
// (FitResult::phases), each phase's median over the repeats.
json breakdown(const fit::FitData& d, int repeats) {
  std::vector<fit::FitPhases> runs;
  for (int k = 0; k < std::max(1, repeats); ++k) runs.push_back(fit::fit_knob(d).phases);
  struct Phase {
    const char* name;
    const char* what;
    double fit::FitPhases::*field;
  };
  const Phase phases[] = {
      {"start", "moving samples, linear fit, detent search", &fit::FitPhases::start},
      {"cells", "building and factoring the position cells", &fit::FitPhases::cells},
      {"solve", "Levenberg-Marquardt (Ceres), all runs", &fit::FitPhases::solve},
      {"stick_band", "Eq. 7 estimate, leaving the band out", &fit::FitPhases::stick_band},
      {"trim", "robust scale, leaving outliers out", &fit::FitPhases::trim},
      {"covariance", "sandwich covariance, CIs, torque band, summary", &fit::FitPhases::covariance},
  };
  std::cout << "\nknoblab phases (median of " << runs.size() << " fits, wall time)\n";
  json out = json::object();
  double total = 0.0;
  for (const Phase& p : phases) {
    std::vector<double> t;
    for (const fit::FitPhases& r : runs) t.push_back(r.*(p.field));
    std::nth_element(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(t.size() / 2), t.end());
    const double med = t[t.size() / 2];
    total += med;
    std::cout << "  " << pad(p.name, 12) << fmt("%8.2f ms  ", 1e3 * med) << p.what << "\n";
    out[p.name] = {{"median_s", med}, {"what", p.what}};
  }
  std::cout << "  " << pad("sum", 12) << fmt("%8.2f ms", 1e3 * total) << "\n";
  return out;
}

int run(const Options& o) {
  fit::ValidationSpec spec;
  spec.samples = o.samples;
  spec.seed = o.seed;
  const std::vector<double> truth = spec.params;
  const fit::FitData d = fit::make_validation_data(spec);

  // knoblab, in-process, from no starting values.
  Timing tk;
  const fit::FitResult r = timed(o.repeats, tk, [&] { return fit::fit_knob(d); });
  if (r.params.size() != truth.size()) throw std::runtime_error("knoblab fitted the wrong model");
  const Errors ek = errors_of(r.params, truth, d);

  std::optional<json> peer;
  std::optional<fs::path> csv;
  if (o.peer) {
    csv = o.csv_path.empty()
              ? fs::temp_directory_path() /
                    ("knoblab-fit-bench-" + std::to_string(::getpid()) + ".csv")
              : fs::path(o.csv_path);
    write_csv(d, *csv);
    try {
      peer = run_peer(*csv, std::max(3, o.repeats));
    } catch (...) {
      if (o.csv_path.empty()) fs::remove(*csv);
      throw;
    }
    if (o.csv_path.empty()) fs::remove(*csv);
  } else if (!o.csv_path.empty()) {
    write_csv(d, o.csv_path);
  }

  // The peer's fastest variant is what knoblab is compared with.
  const json* best = nullptr;
  std::vector<double> ps;
  Errors es;
  if (peer) {
    for (const json& v : (*peer)["variants"]) {
      if (v["name"] == (*peer)["best"]) best = &v;
    }
    if (!best) throw std::runtime_error("the peer's best variant is missing");
    ps = (*best)["params"].get<std::vector<double>>();
    es = errors_of(ps, truth, d);
  }

  // ---- report ----
  const auto names = r.names;
  std::cout << "knoblab fit benchmark: thesis Eq. 6, " << d.size() << " samples ("
            << fmt("%.1f", static_cast<double>(d.size()) / spec.rate_hz) << " s at "
            << fmt("%.0f", spec.rate_hz) << " Hz), noise seed " << o.seed << "\n\n";
  const std::string sname = best ? "scipy " + (*best)["name"].get<std::string>() : "";
  std::cout << std::string(22, ' ') << "knoblab         " << sname << "\n";
  auto row = [&](const std::string& label, const std::string& a, const std::string& b) {
    std::cout << pad(label, 22) << pad(a, 16) << b << "\n";
  };
  row("start", "none (searched)", best ? "true parameters" : "");
  row("time median [s]", fmt("%.4f", tk.median_s()),
      best ? fmt("%.4f", (*best)["seconds"].get<double>()) : "");
  {
    double smin = 0;
    if (best) {
      const auto runs = (*best)["runs"].get<std::vector<double>>();
      smin = *std::min_element(runs.begin(), runs.end());
    }
    row("time min [s]", fmt("%.4f", tk.min_s()), best ? fmt("%.4f", smin) : "");
  }
  row("cpu median [s]", fmt("%.4f", tk.cpu_median_s()),
      best ? fmt("%.4f", (*best)["cpu_seconds"].get<double>()) : "");
  row("iterations / nfev", std::to_string(r.iterations),
      best ? std::to_string((*best)["nfev"].get<int>()) : "");
  row("rms residual [N·m]", fmt("%.9f", ek.rmse_Nm), best ? fmt("%.9f", es.rmse_Nm) : "");
  row("max |param err| [%]", fmt("%.5f", ek.max_abs_rel_pct),
      best ? fmt("%.5f", es.max_abs_rel_pct) : "");
  row("rms param err [%]", fmt("%.5f", ek.rms_rel_pct), best ? fmt("%.5f", es.rms_rel_pct) : "");

  std::cout << "\nparameter    truth    knoblab         err [%]    ±ci95 [%]"
            << (best ? "   scipy           err [%]" : "") << "\n";
  for (std::size_t k = 0; k < truth.size(); ++k) {
    std::string n(names[k]);
    n.resize(13, ' ');
    std::cout << n << fmt("%-9.3g", truth[k]) << fmt("%-16.10g", r.params[k])
              << fmt("%+-11.5f", ek.rel_pct[k])
              << fmt("%-12.5f", 100.0 * (r.ci95[k][1] - r.params[k]) / std::abs(truth[k]));
    if (best) std::cout << "   " << fmt("%-16.10g", ps[k]) << fmt("%+.5f", es.rel_pct[k]);
    std::cout << "\n";
  }
  if (!r.detents) {
    std::cout << "(knoblab found no detents in these data: A_pos, P_pos, S_pos held)\n";
  }
  if (r.stick) {
    std::cout << "(knoblab found a stick band |ω| < " << fmt("%.3g", r.stick->dv)
              << " rad/s and fitted the " << r.samples << " samples outside it)\n";
  }

  json figures = {
      {"samples", d.size()},
      {"rate_hz", spec.rate_hz},
      {"seed", o.seed},
      {"truth", truth},
      {"names", names},
      {"knoblab",
       {{"start", "none"},
        {"repeats", o.repeats},
        {"median_s", tk.median_s()},
        {"min_s", tk.min_s()},
        {"cpu_median_s", tk.cpu_median_s()},
        {"runs_s", tk.wall},
        {"params", r.params},
        {"ci95", r.ci95},
        {"iterations", r.iterations},
        {"fit_seconds", r.seconds},
        {"rmse_fit_Nm", r.rmse_Nm},
        {"samples_fitted", r.samples},
        {"detents", r.detents},
        {"errors", errors_json(ek)}}},
  };

  if (best) {
    std::cout << "\nscipy variants (start: true parameters; median of "
              << (*peer)["repeats"].get<int>() << ")\n";
    for (const json& v : (*peer)["variants"]) {
      std::string n = v["name"].get<std::string>();
      n.resize(14, ' ');
      const Errors ev = errors_of(v["params"].get<std::vector<double>>(), truth, d);
      std::cout << "  " << n << fmt("%9.4f s", v["seconds"].get<double>())
                << fmt("  cpu %8.4f s", v["cpu_seconds"].get<double>())
                << "  nfev " << v["nfev"].get<int>() << fmt("  rms residual %.9f", ev.rmse_Nm)
                << fmt("  ratio %6.2f×", v["seconds"].get<double>() / tk.median_s())
                << (v["ok"].get<bool>() ? "" : "  (did not converge)") << "\n";
    }
    const double ratio = (*best)["seconds"].get<double>() / tk.median_s();
    const double cpu_ratio = (*best)["cpu_seconds"].get<double>() / tk.cpu_median_s();
    const Verdict v = compare(r.params, ps, r.se, ek, es);
    std::cout << "\nratio (scipy fastest / knoblab, median wall): " << fmt("%.2f×", ratio)
              << "   (cpu time: " << fmt("%.2f×", cpu_ratio) << ")\n";
    std::cout << "errors: parameters " << v.params << ", rms residual " << v.residual << "\n";
    if (ratio >= 1.0) {
      std::cout << "knoblab is " << fmt("%.1f", ratio) << "× faster; error " << v.overall << "\n";
    } else {
      std::cout << "knoblab is " << fmt("%.1f", 1.0 / ratio) << "× slower (" << fmt("%.2f", ratio)
                << "× faster); error " << v.overall << "\n";
    }
    const bool met = ratio >= kTargetRatio && v.overall != "worse";
    std::cout << "target (≥ " << fmt("%.0f", kTargetRatio) << "× faster, error equal or better): "
              << (met ? "met" : "MISSED") << "\n";
    figures["scipy"] = *peer;
    figures["scipy"]["errors"] = errors_json(es);
    figures["ratio"] = ratio;
    figures["cpu_ratio"] = cpu_ratio;
    figures["error_verdict"] = {
        {"params", v.params}, {"residual", v.residual}, {"overall", v.overall}};
    figures["target"] = {{"ratio", kTargetRatio}, {"met", met}};
  }

  if (o.breakdown) figures["breakdown"] = breakdown(d, o.repeats);

  if (!o.json_path.empty()) {
    std::ofstream f(o.json_path);
    f << figures.dump(2) << "\n";
    if (!f) throw std::runtime_error("cannot write " + o.json_path);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse_args(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "knoblab-fit-bench: " << e.what() << "\n";
    usage(std::cerr);
    return 1;
  }
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "knoblab-fit-bench: " << e.what() << "\n";
    return 1;
  }
}
