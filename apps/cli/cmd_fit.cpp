// knoblab fit: fit the knob model to a capture (thesis Ch. 2, Eq. 6 and 7).
#include <cstdio>
#include <filesystem>

#include "cancel.hpp"
#include "capture_input.hpp"
#include "commands.hpp"
#include "figure_args.hpp"
#include "fit_run.hpp"
#include "model_fit_run.hpp"
#include "progress.hpp"
#include "provenance.hpp"
#include "result_files.hpp"
#include "knoblab/fit/render_model.hpp"
#include "knoblab/fit/report.hpp"
#include "knoblab/fit/result_json.hpp"

namespace knoblab::cli {

const CommandSpec kFitSpec{
    "fit",
    "(FILE.csv | --capture ID --db FILE.sqlite) [--model thesis6|render4|MODEL.json] [--json OUT.json|-]\n"
    "       [--report DIR [--format pdf,svg,png] [--size 160x100mm] [--dpi 300]]\n"
    "       [--render-model OUT.json] [--linear]",
    "Fit the knob model (thesis Eq. 6 with the Eq. 7 stick band) to a capture.\n"
    "Prints the parameters with 95% confidence intervals (text in mN·m, degrees; the JSON\n"
    "in SI units), detents per revolution and how well the model fits. A linear actuator's\n"
    "capture ('# axis: linear' in its CSV, or --linear) is told in N, mm, N·s/m and kg, its\n"
    "detents as a period in mm. --report writes the figures as PDF, SVG and PNG, each with\n"
    "its data as CSV (docs/figures.md). A capture from the store gets its fit stored\n"
    "beside it, with the report files and its provenance (knoblab fits, knoblab results).\n"
    "Ctrl-C cancels it: nothing is written or stored, exit status 130.\n"
    "--model MODEL.json fits a model file's terms instead (discrepancy --model-out: Eq. 6\n"
    "and the effects found), from its values, and --json writes the refitted model file.",
    with_figure_options({{"capture", true, "capture id in the store (instead of FILE.csv)"},
     {"db", true, "sqlite store"},
     {"model", true, "thesis6 (Eq. 6, default), render4 (Eq. 14: M, B, A, P) or a model file's terms",
      "thesis6|render4|MODEL.json"},
     {"json", true, "write the fit as JSON (docs/fit.md); '-' for stdout"},
     {"report", true, "directory for the report figures and fit.json"},
     {"render-model", true, "write the render model file hapticd loads (--model)"},
     {"alpha", true, "accel (default: the α column, when the CSV has one) or encoder (θ'')", "accel|encoder"},
     {"no-filter", false, "skip the Table 6 low-pass filters (data already clean)"},
     {"detents", true, "auto (default), yes or no", "auto|yes|no"},
     {"no-stick", false, "do not estimate the Karnopp stick band"},
     kLinearOption,
     kQuietOption}),
    0, 1, true,
    {"knoblab simulate --knob moderate-detents --out knob.csv && knoblab fit knob.csv",
     "knoblab fit --capture 1 --db lab.sqlite --json fit.json --render-model knob-model.json",
     "knoblab fit knob.csv --report figures/ --format pdf,png --size 90x60mm --dpi 600",
     "knoblab fit again.csv --model knob-model.json --json refitted-model.json"}};

int run_fit(const Args& args) {
  const fit::PrepOptions prep = prep_options(args);
  fit::FitOptions opt;
  if (auto m = args.get("model")) {
    const auto kind = fit::parse_model(*m);
    if (!kind && std::filesystem::is_regular_file(*m)) return run_fit_model_file(args, *m);
    if (!kind)
      throw UsageError("--model must be thesis6, render4 or a model file (discrepancy --model-out); "
                       "no file '" + *m + "'");
    opt.model = *kind;
  }
  if (auto d = args.get("detents")) {
    if (*d == "auto") opt.detents = fit::FitOptions::Detents::Auto;
    else if (*d == "yes") opt.detents = fit::FitOptions::Detents::Force;
    else if (*d == "no") opt.detents = fit::FitOptions::Detents::None;
    else throw UsageError("--detents must be auto, yes or no");
  }
  opt.stick_band = !args.has("no-stick");
  const fit::plot::FigureOptions figures = figure_options(args);  // checked before any work
  if (args.get("report") == std::optional<std::string>("")) throw UsageError("--report needs a directory");

  Progress progress = Progress::on_stderr(args, "fit");
  const CancelOnSignal cancel;
  opt.hooks = progress.hooks();
  progress.show("reading the input");
  CaptureInput in = read_capture_input(args);
  const std::string& title = in.title;
  throw_if_cancelled();

  const FitRun run = fit_capture(in.capture, prep, opt);
  const fit::FitResult& r = run.result;
  const std::string json = fit::to_json(r);
  const std::string render_model = fit::to_json(fit::reduce_to_render(r, run.data.omega));
  std::vector<store::ResultFile> files;  // the report, drawn aside until the fit is kept
  if (args.has("report")) {
    const StagedReport staged;
    fit::ReportOptions ro;
    ro.figure = figures;
    ro.hooks = opt.hooks;
    ro.title = title;
    fit::write_report(r, run.data, fit::predict(r, run.data), staged.dir(), ro);
    staged.add("fit.json", json + "\n");
    // What hapticd renders of this fit (load_model), so that a stored fit
    // can be felt without fitting again (knoblab-ui's "Feel it").
    staged.add("render_model.json", render_model + "\n");
    files = staged.files();
  }
  // The last chance to cancel: from here the fit is written out whole.
  throw_if_cancelled();
  progress.clear();

  const bool json_to_stdout = args.get("json") == std::optional<std::string>("-");
  if (!json_to_stdout) {
    std::printf("%s\n", title.c_str());
    print_fit(stdout, r);
  }
  if (auto out = args.get("json")) write_text(*out, json);
  if (auto out = args.get("render-model")) write_text(*out, render_model);
  if (auto dir = args.get("report")) {
    write_result_files(files, *dir);
    if (!json_to_stdout) std::printf("report: %zu files in %s\n", files.size(), dir->c_str());
  }
  if (in.db && in.capture_id) {
    const std::int64_t fit_id = in.db->insert_fit(*in.capture_id, fit::model_name(r.model), fit::knob_json(r),
                                                  json, files,
                                                  provenance_of(in.sha256, fit_options_json(prep, opt)));
    if (!json_to_stdout) std::printf("stored as fit %lld\n", static_cast<long long>(fit_id));
  }
  return 0;
}

}  // namespace knoblab::cli
