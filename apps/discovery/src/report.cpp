// The discrepancy report's figures (report.hpp): what goes on each, from the
// result's residual trace; the summary's text is report_summary.cpp's, the
// drawing apps/fit's plot module's.
#include "knoblab/discovery/report.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "knoblab/discovery/whiteness.hpp"
#include "knoblab/fit/plot/reduce.hpp"
#include "knoblab/fit/plot/text.hpp"
#include "knoblab/interchange/atomic_file.hpp"
#include "knoblab/model/quantile.hpp"
#include "report_summary.hpp"

namespace knoblab::discovery {

namespace {

namespace fs = std::filesystem;
namespace plot = fit::plot;
using plot::Mark;
using plot::Panel;
namespace palette = plot::palette;

constexpr const char* kWho = "knoblab::discovery::write_discrepancy_report: ";

struct Inputs {
  const DiscrepancyResult& r;
  const ReportOptions& opt;
  ResidualFigures before, after;
  const fit::AxisUnits& u;  // SI → the figures' units (mN·m, deg; N, mm), at the edge only
};

std::string str(std::string_view s) { return std::string(s); }

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string titled(const Inputs& in, const std::string& what) {
  return in.opt.title.empty() ? what : plot::escape(in.opt.title) + " — " + what;
}

std::string rows_subtitle(const Inputs& in) {
  return std::to_string(in.r.train_rows) + " training rows (grey), " + std::to_string(in.r.heldout_rows) +
         " held-out rows (blue: " + (in.r.heldout_recording ? "another recording" : "odd time blocks") +
         "); near-stuck rows left out";
}

// The effects found, in order, an effect found more than once named once
// with its count: "detent_shape, periodic_torque ×3".
std::string added_effects(const DiscrepancyResult& r) {
  std::vector<std::pair<std::string, int>> named;
  for (const Finding& f : r.findings) {
    const std::string name(effect_name(f.effect));
    auto it = std::find_if(named.begin(), named.end(), [&](const auto& n) { return n.first == name; });
    if (it == named.end()) named.push_back({name, 1});
    else ++it->second;
  }
  std::string s;
  for (const auto& [name, count] : named)
    s += (s.empty() ? "" : ", ") + name + (count > 1 ? " ×" + std::to_string(count) : "");
  return s;
}

// A panel's ± y limit (presented, mN·m or N): its own residual's 99.5th
// percentile of |r|, so a few transients do not flatten it, and the after
// panel, with less left to show, is not drawn at the before panel's scale.
double residual_limit(const std::vector<double>& res, const fit::Unit& torque) {
  std::vector<double> a;
  a.reserve(res.size());
  for (const double v : res)
    if (std::isfinite(v)) a.push_back(std::abs(v));
  if (a.empty()) return 1.0;
  const double lim = 1.1 * torque(model::quantile(std::move(a), 0.995));
  return lim > 0.0 ? lim : 1.0;
}

plot::Series dots(std::string name, std::string label, plot::Rgb color, double size, int rank) {
  plot::Series s;
  s.name = std::move(name);
  s.label = std::move(label);
  s.mark = Mark::Dots;
  s.color = color;
  s.size_mm = size;
  s.legend_rank = rank;
  return s;
}

// Residual against x: training rows grey, held-out rows blue over them;
// `added` (final − base model torque) in red when given.
Panel residual_panel(const Inputs& in, const std::vector<double>& x, const std::vector<double>& res,
                     const std::vector<double>* added, std::string name, std::string heading,
                     const std::string& xlabel) {
  const ResidualTrace& tr = in.r.trace;
  Panel p;
  p.name = std::move(name);
  p.heading = std::move(heading);
  p.xlabel = xlabel;
  const fit::Unit& torque = in.u.torque;
  p.ylabel = "residual (" + str(torque.axis_label()) + ")";
  const double limit = residual_limit(res, torque);
  p.y_lo = -limit;
  p.y_hi = limit;
  std::size_t beyond = 0;
  for (const double v : res) beyond += std::abs(torque(v)) > limit ? 1 : 0;
  if (beyond > 0)
    p.heading += " (" + std::to_string(beyond) + " beyond ±" + fmt("%.3g", limit) + " " + str(torque.text) + ")";
  plot::Series train = dots("training_rows", "training rows", palette::kRaw, 0.35, 0);
  plot::Series held = dots("heldout_rows", "held-out rows", palette::kBlue, 0.35, 1);
  // The model's part over the data, small and translucent: the residual stays visible.
  plot::Rgb red = palette::kRed;
  red.alpha = 0.45;
  plot::Series add = dots("final_minus_base_model", "final − base model", red, 0.2, 2);
  for (const std::size_t i : plot::thin(tr.size(), in.opt.max_points)) {
    plot::Series& s = tr.heldout[i] ? held : train;
    s.x.push_back(x[i]);
    s.y.push_back(torque(res[i]));
    if (added) {
      add.x.push_back(x[i]);
      add.y.push_back(torque((*added)[i]));
    }
  }
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  plot::Series zero;
  zero.name = "zero";
  zero.mark = Mark::Line;
  zero.size_mm = 0.2;
  zero.x = {*lo, *hi};
  zero.y = {0.0, 0.0};
  p.series.push_back(std::move(train));
  p.series.push_back(std::move(held));
  p.series.push_back(std::move(zero));
  if (added) p.series.push_back(std::move(add));
  return p;
}

plot::Figure residual_figure(const Inputs& in, const std::vector<double>& x, const std::string& what,
                             const std::string& xlabel, std::string x_column) {
  const DiscrepancyResult& r = in.r;
  std::vector<double> added;
  if (!r.findings.empty()) {
    added.resize(r.trace.size());
    for (std::size_t i = 0; i < added.size(); ++i) added[i] = r.trace.before[i] - r.trace.after[i];
  }
  auto figures = [&in](const ModelSummary& m) {
    return "held-out RMS " + in.u.torque.with(m.heldout_rmse_Nm, "%.4g") + ", fit " + fmt("%.1f", m.fit_percent) + " %";
  };
  plot::Figure f;
  f.title = titled(in, "residual against " + what + ", before and after");
  f.subtitle = rows_subtitle(in);
  f.x_column = std::move(x_column);
  f.y_column = "residual_" + str(in.u.torque.column_suffix());
  f.panels.push_back(residual_panel(in, x, r.trace.before, added.empty() ? nullptr : &added, "before",
                                    "Before: base model (Eq. 6) — " + figures(r.base), xlabel));
  const std::string final_name = !r.findings.empty()    ? "+ " + added_effects(r)
                                 : r.tentative.empty() ? "= base, nothing is missing"
                                                       : "= base, tentative only";
  f.panels.push_back(residual_panel(in, x, r.trace.after, nullptr, "after",
                                    "After: " + final_name + " — " + figures(r.final_model),
                                    xlabel));
  return f;
}

// Stems of a correlation with its 99 % band shaded about zero.
Panel correlation_panel(const Correlation& c, std::string name, std::string heading, const std::string& xlabel,
                        double limit) {
  Panel p;
  p.name = std::move(name);
  p.heading = std::move(heading);
  p.xlabel = xlabel;
  p.ylabel = "correlation";
  p.y_lo = -limit;
  p.y_hi = limit;
  if (c.lags.empty()) return p;
  const double x0 = c.lags.front() - 0.5, x1 = c.lags.back() + 0.5;
  const double b = std::isfinite(c.band) ? c.band : 0.0;
  plot::Series band;
  band.name = "band_99";
  band.mark = Mark::Fill;
  band.color = palette::kBandLight;
  band.x = {x0, x1};
  band.y = {b, b};
  band.y_low = {-b, -b};
  plot::Series zero;
  zero.name = "zero";
  zero.mark = Mark::Line;
  zero.size_mm = 0.2;
  zero.x = {x0, x1};
  zero.y = {0.0, 0.0};
  plot::Series stems;
  stems.name = "correlation";
  stems.mark = Mark::Stems;
  stems.color = palette::kBlue;
  stems.size_mm = 0.3;
  for (std::size_t k = 0; k < c.lags.size(); ++k) {
    stems.x.push_back(c.lags[k]);
    stems.y.push_back(c.r[k]);
  }
  p.series.push_back(std::move(band));
  p.series.push_back(std::move(zero));
  p.series.push_back(std::move(stems));
  return p;
}

double correlation_limit(const Correlation& a, const Correlation& b) {
  double lim = 0.05;
  for (const Correlation* c : {&a, &b}) {
    for (const double v : c->r) lim = std::max(lim, std::abs(v));
    if (std::isfinite(c->band)) lim = std::max(lim, 2.0 * c->band);
  }
  return std::min(1.0, 1.15 * lim);
}

plot::Figure whiteness_figure(const Inputs& in) {
  const TraceRows& rows = in.before.rows;
  const std::string spacing = fmt("%.3g", rows.row_spacing_s * 1e3);
  plot::Figure f;
  const std::string omega(in.u.omega);
  f.title = titled(in, "residual whiteness (Ljung–Box) and independence of " + omega);
  f.subtitle = std::string(rows.heldout ? "held-out rows" : "all rows") + ", lags in rows of " + spacing +
               " ms; 99 % bands shaded; p < 0.01: not white / depends on " + omega;
  f.columns = 2;
  f.x_column = "lag_rows";
  f.y_column = "correlation";
  f.y_low_column = "correlation_lower";
  const std::string xlabel = "lag (rows of " + spacing + " ms)";
  using detail::format_p;
  const ResidualFigures &b = in.before, &a = in.after;
  const double wl = correlation_limit(b.whiteness, a.whiteness);
  const double il = correlation_limit(b.independence, a.independence);
  f.panels.push_back(correlation_panel(b.whiteness, "autocorrelation_before",
                                       "Autocorrelation, before — p " + format_p(b.whiteness.p), xlabel, wl));
  f.panels.push_back(correlation_panel(a.whiteness, "autocorrelation_after",
                                       "Autocorrelation, after — p " + format_p(a.whiteness.p), xlabel, wl));
  f.panels.push_back(correlation_panel(b.independence, "velocity_correlation_before",
                                       "Correlation with " + omega + ", before — p " + format_p(b.independence.p), xlabel,
                                       il));
  f.panels.push_back(correlation_panel(a.independence, "velocity_correlation_after",
                                       "Correlation with " + omega + ", after — p " + format_p(a.independence.p), xlabel,
                                       il));
  return f;
}

plot::Figure summary_figure(const Inputs& in, const detail::SummaryText& s) {
  plot::Figure f;
  f.title = titled(in, "what the thesis model leaves out");
  f.subtitle = in.r.findings.empty()
                   ? (in.r.tentative.empty() ? "no finding" : "no finding (tentative terms under the bar)")
                   : std::to_string(in.r.findings.size()) + " finding" + (in.r.findings.size() > 1 ? "s" : "") +
                         ": " + added_effects(in.r);
  for (const auto& row : s.table) {
    f.text.table.emplace_back();
    for (const std::string& cell : row) f.text.table.back().push_back(plot::escape(cell));
  }
  for (const std::string& p : s.findings) f.text.paragraphs.push_back(plot::escape(p));
  for (const std::string& n : s.notes) f.text.notes.push_back(plot::escape(n));
  return f;
}

void check(const DiscrepancyResult& r, const ReportOptions& opt) {
  const ResidualTrace& tr = r.trace;
  const std::size_t n = tr.size();
  if (n == 0) throw std::invalid_argument(std::string(kWho) + "the result has no residual trace");
  for (const std::size_t m :
       {tr.theta.size(), tr.omega.size(), tr.torque.size(), tr.before.size(), tr.after.size(), tr.heldout.size()})
    if (m != n)
      throw std::invalid_argument(std::string(kWho) + "trace columns differ in length (" + std::to_string(m) +
                                  " vs " + std::to_string(n) + ")");
  if (opt.max_points == 0) throw std::invalid_argument(std::string(kWho) + "max_points must be positive");
}

std::vector<double> presented(const std::vector<double>& v, const fit::Unit& unit) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = unit(v[i]);
  return out;
}

// The figures and summary.md's text, from one pass over the result.
struct Report {
  std::vector<plot::NamedFigure> figures;
  std::string markdown;
};

Report build(const fit::FitData& data, const DiscrepancyResult& r, const ReportOptions& opt) {
  check(r, opt);
  const fit::AxisUnits& u = fit::units(r.axis);
  const Inputs in{r, opt, residual_figures(r.trace, r.trace.before), residual_figures(r.trace, r.trace.after), u};
  const detail::SummaryText text = detail::summary_text(data, r, in.before, in.after);
  const auto label = [](std::string_view what, std::string_view symbol, const fit::Unit& unit) {
    return str(what) + " " + str(symbol) + " (" + str(unit.axis_label()) + ")";
  };
  Report out;
  out.figures = {
      {"residual_position", residual_figure(in, presented(r.trace.theta, u.position), "position",
                                            label("position", u.theta, u.position),
                                            "position_" + str(u.position.column_suffix()))},
      {"residual_velocity", residual_figure(in, presented(r.trace.omega, u.plot_speed), "velocity",
                                            label("velocity", u.omega, u.plot_speed),
                                            "velocity_" + str(u.plot_speed.column_suffix()))},
      {"residual_time", residual_figure(in, r.trace.t, "time", "time (s)", "time_s")},
      {"whiteness", whiteness_figure(in)},
      {"summary", summary_figure(in, text)},
  };
  out.markdown = detail::summary_markdown(opt.title, text);
  return out;
}

}  // namespace

std::vector<plot::NamedFigure> discrepancy_figures(const fit::FitData& data, const DiscrepancyResult& r,
                                                   const ReportOptions& opt) {
  return build(data, r, opt).figures;
}

std::vector<fs::path> write_discrepancy_report(const fs::path& dir, const fit::FitData& data,
                                               const DiscrepancyResult& r, const ReportOptions& opt) {
  const Report report = build(data, r, opt);
  std::vector<fs::path> written;
  try {
    written = plot::write_figures(report.figures, dir, opt.figure, [&opt](std::size_t done, std::size_t total) {
      opt.hooks.report("drawing the report", done, total);
      opt.hooks.check();
    });
    const fs::path md = dir / "summary.md";
    interchange::write_file_atomically(md, report.markdown);
    written.push_back(md);
  } catch (const fit::Cancelled&) {
    throw;  // as it is: the command says "cancelled"
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(kWho) + e.what());
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(kWho) + e.what());
  }
  return written;
}

}  // namespace knoblab::discovery
