// The summary table and sentences (report_summary.hpp). SI inside, mN·m
// (N on a linear axis) only here, where the text is made.
#include "report_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace knoblab::discovery::detail {

namespace {

constexpr const char* kDash = "–";

std::string fmt(const char* f, double v) {
  if (!std::isfinite(v)) return kDash;
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Spread ‖y − ȳ‖/√N of the torque over the figure rows: fit % after each
// finding follows from its held-out RMS when those rows are the held-out ones.
double torque_spread(const DiscrepancyResult& r, const TraceRows& rows) {
  double mean = 0.0, ss = 0.0;
  for (const std::size_t i : rows.rows) mean += r.trace.torque[i];
  mean /= static_cast<double>(rows.rows.size());
  for (const std::size_t i : rows.rows) ss += (r.trace.torque[i] - mean) * (r.trace.torque[i] - mean);
  return std::sqrt(ss / static_cast<double>(rows.rows.size()));
}

}  // namespace

std::string format_p(double p) {
  if (!std::isfinite(p)) return kDash;
  if (p < 1e-12) return "< 1e-12";
  return fmt(p >= 1e-3 ? "%.3f" : "%.1e", p);
}

SummaryText summary_text(const fit::FitData& data, const DiscrepancyResult& r,
                         const ResidualFigures& before, const ResidualFigures& after) {
  SummaryText s;
  const fit::AxisUnits& u = fit::units(r.axis);
  const fit::Unit& torque = u.torque;
  const std::string tq(torque.text), omega(u.omega), theta(u.theta);
  s.table.push_back({"model", "RMS\n" + tq, "held-out\nRMS " + tq,
                     before.rows.heldout ? "fit %\nheld-out" : "fit %\nall rows", "BIC",
                     "white\np", omega + "-indep.\np", "forward " + theta + "\nRMS " + std::string(u.fine_position.text)});
  auto row = [&](std::string name, const ModelSummary& m) {
    s.table.push_back({std::move(name), fmt("%.4g", torque(m.rmse_Nm)),
                       fmt("%.4g", torque(m.heldout_rmse_Nm)), fmt("%.1f", m.fit_percent),
                       fmt("%.0f", m.bic), format_p(m.whiteness_p), format_p(m.independence_p),
                       std::isfinite(m.forward_rmse_rad) ? fmt("%.3g", u.fine_position(m.forward_rmse_rad)) : kDash});
  };
  row("base (Eq. 6)", r.base);
  const double spread = before.rows.heldout && !before.rows.rows.empty()
                            ? torque_spread(r, before.rows)
                            : std::nan("");
  for (std::size_t k = 0; k < r.findings.size(); ++k) {
    const Finding& f = r.findings[k];
    const std::string name = "+ " + std::string(effect_name(f.effect));
    if (k + 1 == r.findings.size()) {
      row(name + " (final)", r.final_model);
      continue;
    }
    // Only the error figures are known here: the trace keeps the base's and
    // the final model's residuals.
    s.table.push_back({name, fmt("%.4g", torque(f.rmse_after_Nm)),
                       fmt("%.4g", torque(f.heldout_rmse_after_Nm)),
                       fmt("%.1f", 100.0 * (1.0 - f.heldout_rmse_after_Nm / spread)),
                       fmt("%.0f", f.bic_after), kDash, kDash, kDash});
  }
  if (r.findings.empty()) row("final (nothing added)", r.final_model);

  for (std::size_t k = 0; k < r.findings.size(); ++k)
    s.findings.push_back(std::to_string(k + 1) + ". " + r.findings[k].explanation);
  if (r.findings.empty() && r.tentative.empty())
    s.findings.push_back(
        "Nothing is missing: no effect from the library lowered the held-out error, so the "
        "thesis model (Eq. 6) describes this recording as well as the library can.");
  if (!r.tentative.empty()) {
    const double gain = 1.0 - r.tentative_heldout_rmse_Nm / r.base.heldout_rmse_Nm;
    s.findings.push_back("Nothing is reported: the terms below lower the held-out RMS consistently, but only by " +
                         fmt("%.0f", 100.0 * gain) + " % together (" + fmt("%.4g", torque(r.base.heldout_rmse_Nm)) +
                         " → " + torque.with(r.tentative_heldout_rmse_Nm, "%.4g") + "), under the " +
                         fmt("%.0f", 100.0 * r.min_reported_gain) +
                         " % a finding must earn. They are tentative; the final model is the base:");
    for (std::size_t k = 0; k < r.tentative.size(); ++k)
      s.findings.push_back("(" + std::to_string(k + 1) + ") " + r.tentative[k].explanation);
  }

  const std::string effort(u.effort), travel(u.travel);
  const bool linear = r.axis == fit::Axis::Linear;
  s.notes.push_back(
      "Forward view: the model driven by the measured " + effort + " over 20 ms windows begun from the "
      "measured " + travel + " and speed on the held-out rows (M·" + std::string(u.alpha) + " = " + std::string(u.tau) +
      " − the model's other terms); forward " + theta + " RMS is the simulated − measured " + travel +
      ". – when the fitted " + std::string(u.mass) + " is not positive or the model runs away (" +
      (linear ? "a metre" : "a radian") + " off within a window).");
  const std::string held = r.heldout_recording ? "another recording" : "odd time blocks";
  s.notes.push_back("RMS and BIC over the " + std::to_string(r.train_rows) +
                    " training rows, held-out RMS over the " + std::to_string(r.heldout_rows) +
                    " held-out rows (" + held + "), of " + std::to_string(data.size()) +
                    " samples at " + fmt("%.0f", data.rate_hz) + " Hz.");
  const TraceRows& rows = before.rows;
  const double every = rows.row_spacing_s * data.rate_hz;
  s.notes.push_back(
      "fit % (as MATLAB's compare: 100·(1 − ‖y − ŷ‖/‖y − ȳ‖)), whiteness and independence over " +
      std::string(rows.heldout ? "the held-out rows" : "all rows (too few held-out rows)") +
      ". Lags are in trace rows: one row is " + fmt("%.3g", rows.row_spacing_s * 1e3) +
      " ms (" + fmt("%.3g", every) + " sample intervals); lag pairs never span a gap.");
  s.notes.push_back("Whiteness: Ljung–Box Q of the autocorrelation at lags 1…" +
                    std::to_string(before.whiteness.lags.size()) + " (" +
                    fmt("%.0f", before.whiteness.dof) +
                    " dof). Independence: the cross-correlation with " + omega + " at lags ±" +
                    std::to_string(before.whiteness.lags.size()) +
                    ", allowing for the residual's own autocorrelation (" +
                    fmt("%.0f", before.independence.dof) + " and " +
                    fmt("%.0f", after.independence.dof) +
                    " dof before and after). p below 0.01: not white, or not independent of " + omega + ".");
  if (const std::string same = same_rows_sentence(r); !same.empty()) s.notes.push_back(same);
  if (r.findings.size() > 1)
    s.notes.push_back("–: only the error figures are known between findings (the residuals kept "
                      "are the base model's and the final model's); they are over the rows every model "
                      "describes, as the findings' sentences.");
  return s;
}

std::string summary_markdown(const std::string& title, const SummaryText& s) {
  std::string md = "# Discrepancy report" + (title.empty() ? "" : ": " + title) + "\n\n";
  for (std::size_t r = 0; r < s.table.size(); ++r) {
    md += "|";
    for (std::string cell : s.table[r]) {
      std::replace(cell.begin(), cell.end(), '\n', ' ');  // two-line headers on the page
      md += " " + cell + " |";
    }
    md += "\n";
    if (r == 0) {
      md += "|---|";
      for (std::size_t c = 1; c < s.table[r].size(); ++c) md += "---:|";
      md += "\n";
    }
  }
  md += "\n## Findings\n\n";
  for (const std::string& f : s.findings) md += f + "\n";
  md += "\n## Notes\n\n";
  for (const std::string& n : s.notes) md += "- " + n + "\n";
  return md;
}

}  // namespace knoblab::discovery::detail
