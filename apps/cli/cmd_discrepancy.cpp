// knoblab discrepancy: where a recording and the fitted knob model disagree,
// which physics from the effect library is missing, fitted and checked on
// held-out time blocks (docs/discrepancy.md).
#include <cmath>
#include <cstdio>
#include <string>

#include "cancel.hpp"
#include "capture_input.hpp"
#include "commands.hpp"
#include "figure_args.hpp"
#include "progress.hpp"
#include "provenance.hpp"
#include "result_files.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "model_input.hpp"
#include "knoblab/discovery/report.hpp"
#include "knoblab/fit/fit_data.hpp"

namespace knoblab::cli {

const CommandSpec kDiscrepancySpec{
    "discrepancy",
    "(FILE.csv | --capture ID --db FILE.sqlite) [--heldout FILE.csv | --heldout-capture ID]\n"
    "  [--json OUT.json|-] [--model-out FILE.json] [--report DIR [--format pdf,svg,png]\n"
    "  [--size 160x100mm] [--dpi 300]] [--effects LIST] [--max-findings N] [--min-gain PCT]\n"
    "  [--model MODEL.json [--refit]] [--linear]",
    "Find what the thesis model leaves out of a capture, and say which physics it is.\n"
    "Locates the structured residual, fits candidate effects (stribeck, backlash,\n"
    "detent_shape, periodic_torque, …) with the model, keeps those that lower the error on\n"
    "held-out time blocks, and says so (text in mN·m, degrees; the JSON in SI units). A\n"
    "linear actuator's capture ('# axis: linear' in its CSV, or --linear) is told in N, mm,\n"
    "N/m and mm per cycle, without gravity among the candidates (its weight is an offset). A\n"
    "capture from the store gets its result stored beside it, with the report files and\n"
    "its provenance (knoblab results). --model-out writes the final model (base and kept\n"
    "effects) as a model file that knoblab simulate --params, knoblab ctl load_model and\n"
    "hapticd --model take (docs/discrepancy.md). --report writes the figures as PDF, SVG\n"
    "and PNG, each with its data as CSV (docs/figures.md). Ctrl-C cancels it: nothing is\n"
    "written or stored, exit status 130.\n"
    "--model takes the base from a given model instead of fitting Eq. 6 (a fit's JSON, a\n"
    "render model or a model file: the simulation you trust), held as given (--refit: fitted\n"
    "from it), and says what the recording has that the model lacks.",
    with_figure_options({{"capture", true, "capture id in the store (instead of FILE.csv)"},
     {"db", true, "sqlite store"},
     {"heldout", true, "another recording of the knob (CSV), held out whole instead of time blocks"},
     {"heldout-capture", true, "… or its capture id in the store"},
     {"max-findings", true, "stop after N findings (default 4)", "N"},
     {"min-gain", true, "held-out RMS cut, in %, the findings must earn together to be reported (default 20)", "PCT"},
     {"json", true, "write the result as JSON (docs/discrepancy.md); '-' for stdout"},
     {"model-out", true, "write the final model as a model file (simulate --params, ctl load_model)"},
     {"report", true, "directory for the report: residual figures before/after, whiteness, summary"},
     {"effects", true, "comma-separated candidate effect ids (default: all implemented)", "LIST"},
     {"model", true, "the base: a fit's JSON, a render model or a model file, held as given", "MODEL.json"},
     {"refit", false, "with --model: fit the given model's terms to the recording first"},
     {"alpha", true, "accel (default: the α column, when the CSV has one) or encoder (θ'')", "accel|encoder"},
     {"no-filter", false, "skip the Table 6 low-pass filters (data already clean)"},
     kLinearOption,
     kQuietOption}),
    0, 1, true,
    {"knoblab simulate --knob moderate-detents --effects 'stribeck:static_excess_Nm=0.004,stribeck_velocity_rad_s=0.5' "
     "--out knob.csv && knoblab discrepancy knob.csv --report report/",
     "knoblab discrepancy --capture 1 --db lab.sqlite --json found.json --report report/ --format pdf",
     "knoblab discrepancy --model simulation.model.json --input real.csv --report report/"}};

namespace {

std::vector<discovery::EffectId> parse_effects(const std::string& list) {
  std::vector<discovery::EffectId> out;
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    const std::string name = list.substr(at, comma - at);
    const auto id = discovery::parse_effect(name);
    if (!id) {
      std::string known;
      for (const discovery::EffectId e : discovery::kAllEffects)
        known += (known.empty() ? "" : ", ") + std::string(discovery::effect_name(e));
      throw UsageError("unknown effect '" + name + "' in --effects (known: " + known + ")");
    }
    out.push_back(*id);
    at = comma + 1;
  }
  return out;
}

// "RMS 0.73 mN·m, held-out RMS 0.74 mN·m, fit 91.2 %, whiteness p 0.003"
std::string figures(const discovery::ModelSummary& m, const fit::AxisUnits& u) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "RMS %s, held-out RMS %s, fit %.1f %%, whiteness p ",
                u.torque.with(m.rmse_Nm, "%.4g").c_str(), u.torque.with(m.heldout_rmse_Nm, "%.4g").c_str(),
                m.fit_percent);
  char p[32];
  std::snprintf(p, sizeof p, "%.2g", m.whiteness_p);
  std::string out = buf + std::string(m.whiteness_p < 1e-12 ? "< 1e-12" : p);
  if (std::isfinite(m.forward_rmse_rad))
    out += ", forward " + std::string(u.theta) + " RMS " + u.fine_position.with(m.forward_rmse_rad);
  return out;
}

// Gravity is once per revolution: no candidate on a linear axis.
void check_effects_for(fit::Axis axis, const std::vector<discovery::EffectId>& effects) {
  if (axis != fit::Axis::Linear) return;
  for (const discovery::EffectId e : effects)
    if (e == discovery::EffectId::Gravity)
      throw UsageError("--effects gravity: a linear axis has no once-per-revolution torque; the weight of a "
                       "vertical axis's carriage is a constant force, which offset describes");
}

}  // namespace

int run_discrepancy(const Args& args) {
  const fit::PrepOptions prep = prep_options(args);
  discovery::DiscrepancyOptions opt;
  if (auto e = args.get("effects")) opt.effects = parse_effects(*e);
  const long long max_findings = args.integer("max-findings", 4);
  if (max_findings < 0 || max_findings > 16) throw UsageError("--max-findings must be 0 … 16");
  opt.max_findings = static_cast<std::size_t>(max_findings);
  if (auto g = args.get("min-gain")) {
    const double pct = args.number("min-gain", 20.0);
    if (!(pct >= 0.0 && pct < 100.0)) throw UsageError("--min-gain must be 0 … 100 (percent), not " + *g);
    opt.min_reported_gain = pct / 100.0;
  }
  if (args.get("report") == std::optional<std::string>("")) throw UsageError("--report needs a directory");
  if (args.has("refit") && !args.has("model")) throw UsageError("--refit is for a base given with --model");
  std::optional<ModelInput> given;
  if (auto path = args.get("model")) {
    given = read_model_input(*path);
    opt.base_model = given->knob;
    opt.refit_base = args.has("refit");
  }
  const fit::plot::FigureOptions figure_opts = figure_options(args);  // checked before any work
  nlohmann::json options = prep_options_json(prep);
  options["max_findings"] = opt.max_findings;
  options["min_gain_percent"] = 100.0 * opt.min_reported_gain;
  if (given) {
    const nlohmann::json doc = nlohmann::json::parse(given->text);
    options["model"] = {{"file", *args.get("model")},
                        {"model", doc.value("model", "thesis6")},
                        {"params", doc.at("params")},
                        {"effects", doc.value("effects", nlohmann::json::array())},
                        {"refit", opt.refit_base}};
  }

  Progress progress = Progress::on_stderr(args, "discrepancy");
  const CancelOnSignal cancel;
  opt.hooks = progress.hooks();
  progress.show("reading the input");
  CaptureInput in = read_capture_input(args);  // not const: its store takes the result
  progress.show("preparing");
  const fit::FitData data = fit::prepare(in.capture, prep);
  check_effects_for(data.axis, opt.effects);
  options["effects"] = nlohmann::json::array();
  for (const discovery::EffectId e : opt.effects.empty() ? discovery::implemented_effects(data.axis) : opt.effects)
    options["effects"].push_back(std::string(discovery::effect_name(e)));
  throw_if_cancelled();
  const std::optional<CaptureInput> held = read_heldout_input(args);
  options["heldout"] = held ? input_json(*held) : nlohmann::json(nullptr);
  std::optional<fit::FitData> held_data;
  if (held) held_data = fit::prepare(held->capture, prep);
  if (held_data && held_data->axis != data.axis) {
    throw fit::FitDataError("the held-out recording " + held->title + " is " +
                            std::string(fit::axis_name(held_data->axis)) + ", " + in.title + " " +
                            std::string(fit::axis_name(data.axis)) + ": one knob has one axis");
  }
  throw_if_cancelled();
  const discovery::DiscrepancyResult r =
      held_data ? discovery::discover(data, *held_data, opt) : discovery::discover(data, opt);
  const std::string json = discovery::to_json(r);
  std::vector<store::ResultFile> files;  // the report, drawn aside until the result is kept
  if (args.has("report")) {
    const StagedReport staged;
    discovery::ReportOptions ro;
    ro.figure = figure_opts;
    ro.hooks = opt.hooks;
    ro.title = in.title;
    discovery::write_discrepancy_report(staged.dir(), data, r, ro);
    files = staged.files();
  }
  // The last chance to cancel: from here the result is written out whole.
  throw_if_cancelled();
  progress.clear();

  const bool json_to_stdout = args.get("json") == std::optional<std::string>("-");
  const fit::AxisUnits& u = fit::units(data.axis);
  if (!json_to_stdout) {
    std::printf("%s: %zu samples, %zu training and %zu held-out rows%s, %.2f s\n", in.title.c_str(),
                data.size(), r.train_rows, r.heldout_rows,
                held ? (" (from " + held->title + ")").c_str() : "", r.seconds);
    if (data.resampled) {
      std::printf("irregular time stamps: resampled onto their median interval (%.4g Hz)\n", data.rate_hz);
    }
    if (given) {
      std::printf("base model: %s, %s: %s\n", args.get("model")->c_str(),
                  r.base_held ? "held as given" : "refitted from it", figures(r.base, u).c_str());
    } else {
      std::printf("base model: %s\n", figures(r.base, u).c_str());
    }
    if (r.findings.empty() && r.tentative.empty())
      std::printf("no finding: nothing from the effect library improves the held-out error\n");
    if (!r.tentative.empty()) {
      std::printf("no finding: what the library adds cuts the held-out RMS only %.4g → %s (%.0f %%), "
                  "under the %.0f %% a finding must earn (--min-gain); tentative:\n",
                  u.torque(r.base.heldout_rmse_Nm), u.torque.with(r.tentative_heldout_rmse_Nm, "%.4g").c_str(),
                  100.0 * (1.0 - r.tentative_heldout_rmse_Nm / r.base.heldout_rmse_Nm),
                  100.0 * r.min_reported_gain);
      for (const discovery::Finding& f : r.tentative)
        std::printf("  (%s, %s): %s\n", std::string(discovery::effect_name(f.effect)).c_str(), f.where.c_str(),
                    f.explanation.c_str());
    }
    for (const discovery::Finding& f : r.findings) {
      std::printf("- %s (confidence %.2f, %s): %s\n", std::string(discovery::effect_name(f.effect)).c_str(),
                  f.confidence, f.where.c_str(), f.explanation.c_str());
    }
    std::printf("final model: %s\n", figures(r.final_model, u).c_str());
    if (const std::string same = discovery::same_rows_sentence(r); !same.empty()) std::printf("%s\n", same.c_str());
  }
  if (auto out = args.get("json")) write_text(*out, json);
  if (auto out = args.get("model-out")) {
    write_text(*out, discovery::model_file_json(r, data.omega, in.title));
    if (!json_to_stdout) std::printf("model file: %s\n", out->c_str());
  }
  if (auto dir = args.get("report")) {
    write_result_files(files, *dir);
    if (!json_to_stdout) std::printf("report: %zu files in %s\n", files.size(), dir->c_str());
  }
  if (in.db && in.capture_id) {
    const std::int64_t id = in.db->insert_discrepancy(*in.capture_id, json, held ? held->capture_id : std::nullopt,
                                                      files, provenance_of(in.sha256, options));
    if (!json_to_stdout) std::printf("stored as discrepancy %lld\n", static_cast<long long>(id));
  }
  return 0;
}

}  // namespace knoblab::cli
