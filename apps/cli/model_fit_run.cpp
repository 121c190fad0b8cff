#include "model_fit_run.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string_view>

#include "cancel.hpp"
#include "capture_input.hpp"
#include "commands.hpp"
#include "fit_run.hpp"
#include "model_input.hpp"
#include "progress.hpp"
#include "provenance.hpp"
#include "knoblab/discovery/model_file.hpp"
#include "knoblab/model/effect_table.hpp"

namespace knoblab::cli {

namespace {

// An effect parameter's presentation: torques (units starting "N·m") in mN·m,
// everything else in its SI unit; on a linear axis forces in N, positions
// in mm (fit/axis_units.hpp).
fit::Unit effect_presentation(discovery::EffectId e, std::string_view name, fit::Axis axis) {
  const model::EffectParam* p = model::effect_row(e).param(name);
  return fit::effect_param_unit(fit::units(axis), name, p ? p->unit : std::string_view());
}

void print_row(const std::string& name, double value, double ci, const fit::Unit& p) {
  char interval[64];
  if (std::isnan(ci)) {
    std::snprintf(interval, sizeof interval, "(held)");
  } else {
    std::snprintf(interval, sizeof interval, "[%.5g, %.5g]", (value - ci) * p.scale, (value + ci) * p.scale);
  }
  std::printf("  %-32s %12.5g  %-27s %s\n", name.c_str(), value * p.scale, interval, std::string(p.text).c_str());
}

void print_model_fit(const discovery::ModelFit& f, fit::Axis axis) {
  const fit::AxisUnits& u = fit::units(axis);
  std::printf("model: Eq. 6%s + %zu effect%s, %zu moving rows, %.3f s\n", f.knob.detents ? "" : " (no detents)",
              f.knob.effects.size(), f.knob.effects.size() == 1 ? "" : "s", f.rows, f.seconds);
  std::printf("  %-32s %12s  %-27s %s\n", "parameter", "value", "95% CI", "unit");
  for (std::size_t i = 0; i < f.knob.params.size() && i < model::kThesisParamCount; ++i) {
    const std::string name(model::kThesisParamNames[i]);
    print_row(name, f.knob.params[i], f.base_ci95[i], presentation(name, axis));
  }
  for (std::size_t e = 0; e < f.knob.effects.size(); ++e) {
    const discovery::EffectTerm& t = f.knob.effects[e];
    const std::string id(discovery::effect_name(t.effect));
    for (std::size_t k = 0; k < t.params.size(); ++k) {
      const auto& [name, value] = t.params[k];
      print_row(id + "." + name, value, f.effect_ci95[e][k].second, effect_presentation(t.effect, name, axis));
    }
  }
  if (f.knob.stick) {
    std::printf("stick band (Eq. 7, held): dv %s, D- %s, D+ %s\n", u.speed.with(f.knob.stick->dv, "%.4g").c_str(),
                u.torque.with(f.knob.stick->D_neg, "%.4g").c_str(), u.torque.with(f.knob.stick->D_pos, "%.4g").c_str());
  }
  std::printf("rmse %s over the moving rows\n", u.torque.with(f.rmse_Nm, "%.4g").c_str());
}

}  // namespace

int run_fit_model_file(const Args& args, const std::string& model_path) {
  for (const char* option : {"detents", "no-stick", "render-model", "report"}) {
    if (args.has(option)) {
      throw UsageError(std::string("--") + option +
                       " is for the thesis model; with a model file the stick band and the "
                       "effects come from the file, and --json writes a model file hapticd renders");
    }
  }
  const fit::PrepOptions prep = prep_options(args);
  const ModelInput start = read_model_input(model_path);

  Progress progress = Progress::on_stderr(args, "fit");
  const CancelOnSignal cancel;
  const fit::RunHooks hooks = progress.hooks();
  progress.show("reading the input");
  CaptureInput in = read_capture_input(args);
  throw_if_cancelled();
  progress.show("preparing");
  const fit::FitData data = fit::prepare(in.capture, prep);
  const discovery::ModelFit f = discovery::fit_model(data, start.knob, hooks);
  const std::string json = discovery::model_file_json(f, data.omega, in.title, model_path);
  throw_if_cancelled();  // the last chance: from here the fit is written out whole
  progress.clear();

  const bool json_to_stdout = args.get("json") == std::optional<std::string>("-");
  if (!json_to_stdout) {
    std::printf("%s\n", in.title.c_str());
    print_model_fit(f, data.axis);
  }
  if (auto out = args.get("json")) write_text(*out, json);
  if (in.db && in.capture_id) {
    // Provenance: the preparation and the model file's terms the fit started from.
    nlohmann::json options = prep_options_json(prep);
    const nlohmann::json start_doc = nlohmann::json::parse(start.text);
    options["model"] = {{"file", model_path},
                        {"params", start_doc.value("params", nlohmann::json::object())},
                        {"effects", start_doc.value("effects", nlohmann::json::array())}};
    const nlohmann::json doc = nlohmann::json::parse(json);
    const nlohmann::json knob = {{"params", doc.at("params")}, {"stick", doc.at("stick")},
                                 {"effects", doc.at("effects")}};
    const std::int64_t fit_id = in.db->insert_fit(*in.capture_id, "thesis6+effects", knob.dump(), json, {},
                                                  provenance_of(in.sha256, options));
    if (!json_to_stdout) std::printf("stored as fit %lld\n", static_cast<long long>(fit_id));
  }
  return 0;
}

}  // namespace knoblab::cli
