#include "case_analysis.hpp"

#include <chrono>

#include "knoblab/discovery/discrepancy.hpp"

namespace knoblab::bench {

Analysis analyse(const interchange::Capture& capture, fit::FitData* prepared) {
  Analysis a;
  const auto t0 = std::chrono::steady_clock::now();
  const fit::FitData d = fit::prepare(capture);
  const discovery::DiscrepancyResult r = discovery::discover(d);
  a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  a.samples = d.size();
  if (!r.findings.empty()) {
    const discovery::Finding& f = r.findings.front();
    a.named = std::string(discovery::effect_name(f.effect));
    a.confidence = f.confidence;
    a.same_rows_gain = 1.0 - r.same_rows.final_Nm / r.same_rows.base_Nm;
  }
  if (!r.tentative.empty()) a.tentative = std::string(discovery::effect_name(r.tentative.front().effect));
  a.before = r.base.heldout_rmse_Nm;
  a.after = r.final_model.heldout_rmse_Nm;
  a.json = discovery::to_json(r, -1);
  if (prepared) *prepared = d;
  return a;
}

}  // namespace knoblab::bench
