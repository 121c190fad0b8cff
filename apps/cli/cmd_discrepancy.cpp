// knoblab discrepancy: where a recording and the fitted knob model disagree,
// which physics from the effect library is missing, fitted and checked on
// held-out time blocks (docs/discrepancy.md).
#include <cstdio>

#include "capture_input.hpp"
#include "commands.hpp"
#include "knoblab/discovery/discrepancy.hpp"
#include "knoblab/fit/fit_data.hpp"

namespace knoblab::cli {

const CommandSpec kDiscrepancySpec{
    "discrepancy",
    "--input FILE.csv | --capture ID --db FILE [--json OUT] [--effects a,b,…]",
    "Find what the thesis model leaves out of a capture: locate the structured residual,\n"
    "fit candidate effects (stribeck, backlash, detent_shape, periodic_torque, …) with the\n"
    "model, keep those that lower the error on held-out time blocks, and say so.",
    {{"input", true, "interchange CSV"},
     {"capture", true, "capture id in the store"},
     {"db", true, "sqlite store"},
     {"json", true, "write the result as JSON (docs/discrepancy.md); '-' for stdout"},
     {"effects", true, "comma-separated candidate effect ids (default: all implemented)"},
     {"alpha", true, "accel (default: the α column, when the CSV has one) or encoder (θ'')"},
     {"no-filter", false, "skip the Table 6 low-pass filters (data already clean)"}},
    0, 0};

namespace {

std::vector<discovery::EffectId> parse_effects(const std::string& list) {
  std::vector<discovery::EffectId> out;
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    const std::string name = list.substr(at, comma - at);
    const auto id = discovery::parse_effect(name);
    if (!id) throw UsageError("unknown effect '" + name + "' in --effects");
    out.push_back(*id);
    at = comma + 1;
  }
  return out;
}

}  // namespace

int run_discrepancy(const Args& args) {
  const fit::PrepOptions prep = prep_options(args);
  discovery::DiscrepancyOptions opt;
  if (auto e = args.get("effects")) opt.effects = parse_effects(*e);

  const CaptureInput in = read_capture_input(args);
  const fit::FitData data = fit::prepare(in.capture, prep);
  const discovery::DiscrepancyResult r = discovery::discover(data, opt);

  const bool json_to_stdout = args.get("json") == std::optional<std::string>("-");
  if (!json_to_stdout) {
    std::printf("%s: %zu samples, %zu training and %zu held-out rows, %.2f s\n", in.title.c_str(),
                data.size(), r.train_rows, r.heldout_rows, r.seconds);
    std::printf("base model: RMS %.4g mN·m, held-out RMS %.4g mN·m\n", r.base.rmse_Nm * 1e3,
                r.base.heldout_rmse_Nm * 1e3);
    if (r.findings.empty()) std::printf("no finding: nothing from the effect library improves the held-out error\n");
    for (const discovery::Finding& f : r.findings) {
      std::printf("- %s (confidence %.2f, %s): %s\n", std::string(discovery::effect_name(f.effect)).c_str(),
                  f.confidence, f.where.c_str(), f.explanation.c_str());
    }
    std::printf("final model: RMS %.4g mN·m, held-out RMS %.4g mN·m\n", r.final_model.rmse_Nm * 1e3,
                r.final_model.heldout_rmse_Nm * 1e3);
  }
  if (auto out = args.get("json")) write_text(*out, discovery::to_json(r));
  return 0;
}

}  // namespace knoblab::cli
