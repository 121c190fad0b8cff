// The discrepancy report's pages (report.hpp): what goes on each, from the
// result's residual trace. Drawing is report_plot.cpp's, the summary's text
// report_summary.cpp's.
#include "knoblab/discovery/report.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "knoblab/discovery/whiteness.hpp"
#include "knoblab/fit/plplot_shared.hpp"
#include "knoblab/interchange/atomic_file.hpp"
#include "knoblab/model/quantile.hpp"
#include "report_plot.hpp"
#include "report_summary.hpp"

namespace knoblab::discovery {

namespace {

namespace fs = std::filesystem;
using plot::Layer;
using plot::Mark;
using plot::Page;
using plot::Panel;

constexpr double kmNm = 1e3;  // N·m → mN·m, at the edge only
constexpr const char* kWho = "knoblab::discovery::write_discrepancy_report: ";

struct Inputs {
  const DiscrepancyResult& r;
  const ReportOptions& opt;
  ResidualFigures before, after;
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string titled(const Inputs& in, const std::string& what) {
  return in.opt.title.empty() ? what : fit::plplot_escape(in.opt.title) + " — " + what;
}

std::string rows_subtitle(const Inputs& in) {
  return std::to_string(in.r.train_rows) + " training rows (grey), " +
         std::to_string(in.r.heldout_rows) + " held-out rows (blue: " +
         (in.r.heldout_recording ? "another recording" : "odd time blocks") +
         "); near-stuck rows left out";
}

std::string added_effects(const DiscrepancyResult& r) {
  std::string s;
  for (const Finding& f : r.findings) s += (s.empty() ? "" : ", ") + std::string(effect_name(f.effect));
  return s;
}

// Shared ± y limit of the before and after panels (mN·m): the 99.5th
// percentile of |residual| over both, so the after cloud is seen narrower
// and a few transients do not flatten either.
double residual_limit(const ResidualTrace& tr) {
  std::vector<double> a;
  a.reserve(2 * tr.size());
  for (std::size_t i = 0; i < tr.size(); ++i) {
    if (std::isfinite(tr.before[i])) a.push_back(std::abs(tr.before[i]));
    if (std::isfinite(tr.after[i])) a.push_back(std::abs(tr.after[i]));
  }
  if (a.empty()) return 1.0;
  const double lim = 1.1 * kmNm * model::quantile(std::move(a), 0.995);
  return lim > 0.0 ? lim : 1.0;
}

// Residual against x: training rows grey, held-out rows blue over them;
// `added` (final − base model torque) in red when given.
Panel residual_panel(const Inputs& in, const std::vector<double>& x, const std::vector<double>& res,
                     const std::vector<double>* added, std::string heading,
                     const std::string& xlabel, double limit) {
  const ResidualTrace& tr = in.r.trace;
  Panel p;
  p.heading = std::move(heading);
  p.xlabel = xlabel;
  p.ylabel = "residual (mN·m)";
  p.y_lo = -limit;
  p.y_hi = limit;
  Layer train{"training rows", Mark::Dots, plot::kTrain, 2.0, {}, {}, {}};
  Layer held{"held-out rows", Mark::Dots, plot::kHeld, 2.0, {}, {}, {}};
  Layer add{"final − base model", Mark::Dots, plot::kAdded, 1.2, {}, {}, {}};
  const std::size_t n = tr.size(), m = std::min(n, in.opt.max_points);
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = k * n / m;  // thinned evenly
    Layer& l = tr.heldout[i] ? held : train;
    l.x.push_back(x[i]);
    l.y.push_back(kmNm * res[i]);
    if (added) {
      add.x.push_back(x[i]);
      add.y.push_back(kmNm * (*added)[i]);
    }
  }
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  p.layers.push_back(std::move(train));
  p.layers.push_back(std::move(held));
  p.layers.push_back({"", Mark::Line, plot::kBlack, 1.0, {*lo, *hi}, {0.0, 0.0}, {}});
  if (added) p.layers.push_back(std::move(add));
  return p;
}

Page residual_page(const Inputs& in, const std::vector<double>& x, const std::string& what,
                   const std::string& xlabel) {
  const DiscrepancyResult& r = in.r;
  const double limit = residual_limit(r.trace);
  std::vector<double> added;
  if (!r.findings.empty()) {
    added.resize(r.trace.size());
    for (std::size_t i = 0; i < added.size(); ++i) added[i] = r.trace.before[i] - r.trace.after[i];
  }
  auto figures = [](const ModelSummary& m) {
    return "held-out RMS " + fmt("%.4g", m.heldout_rmse_Nm * kmNm) + " mN·m, fit " +
           fmt("%.1f", m.fit_percent) + " %";
  };
  Page page;
  page.title = titled(in, "residual against " + what + ", before and after");
  page.subtitle = rows_subtitle(in);
  page.legends = true;
  page.panels.push_back(residual_panel(in, x, r.trace.before, added.empty() ? nullptr : &added,
                                       "Before: base model (Eq. 6) — " + figures(r.base), xlabel,
                                       limit));
  const std::string final_name =
      !r.findings.empty()    ? "+ " + added_effects(r)
      : r.tentative.empty() ? "= base, nothing is missing"
                            : "= base, tentative only";
  page.panels.push_back(residual_panel(in, x, r.trace.after, nullptr,
                                       "After: " + final_name + " — " + figures(r.final_model),
                                       xlabel, limit));
  return page;
}

// Stems of a correlation with its 99 % band shaded about zero.
Panel correlation_panel(const Correlation& c, std::string heading, const std::string& xlabel,
                        double limit) {
  Panel p;
  p.heading = std::move(heading);
  p.xlabel = xlabel;
  p.ylabel = "correlation";
  p.y_lo = -limit;
  p.y_hi = limit;
  if (c.lags.empty()) return p;
  const double x0 = c.lags.front() - 0.5, x1 = c.lags.back() + 0.5;
  const double b = std::isfinite(c.band) ? c.band : 0.0;
  p.layers.push_back({"", Mark::Fill, plot::kBand, 1.0, {x0, x1}, {b, b}, {-b, -b}});
  p.layers.push_back({"", Mark::Line, plot::kBlack, 1.0, {x0, x1}, {0.0, 0.0}, {}});
  Layer stems{"", Mark::Stems, plot::kHeld, 1.2, {}, {}, {}};
  for (std::size_t k = 0; k < c.lags.size(); ++k) {
    stems.x.push_back(c.lags[k]);
    stems.y.push_back(c.r[k]);
  }
  p.layers.push_back(std::move(stems));
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

Page whiteness_page(const Inputs& in) {
  const TraceRows& rows = in.before.rows;
  Page page;
  page.title = titled(in, "residual whiteness (Ljung–Box) and independence of ω");
  page.subtitle = std::string(rows.heldout ? "held-out rows" : "all rows") +
                  ", lags in rows of " + fmt("%.3g", rows.row_spacing_s * 1e3) +
                  " ms; 99 % bands shaded; p < 0.01: not white / depends on ω";
  page.columns = 2;
  const std::string xlabel = "lag (rows of " + fmt("%.3g", rows.row_spacing_s * 1e3) + " ms)";
  using detail::format_p;
  const ResidualFigures &b = in.before, &a = in.after;
  const double wl = correlation_limit(b.whiteness, a.whiteness);
  const double il = correlation_limit(b.independence, a.independence);
  page.panels.push_back(correlation_panel(
      b.whiteness, "Autocorrelation, before — p " + format_p(b.whiteness.p), xlabel, wl));
  page.panels.push_back(correlation_panel(
      a.whiteness, "Autocorrelation, after — p " + format_p(a.whiteness.p), xlabel, wl));
  page.panels.push_back(correlation_panel(
      b.independence, "Correlation with ω, before — p " + format_p(b.independence.p), xlabel, il));
  page.panels.push_back(correlation_panel(
      a.independence, "Correlation with ω, after — p " + format_p(a.independence.p), xlabel, il));
  return page;
}

Page summary_page(const Inputs& in, const detail::SummaryText& s) {
  Page page;
  page.title = titled(in, "what the thesis model leaves out");
  page.subtitle = in.r.findings.empty()
                      ? (in.r.tentative.empty() ? "no finding" : "no finding (tentative terms under the bar)")
                      : std::to_string(in.r.findings.size()) + " finding" +
                            (in.r.findings.size() > 1 ? "s" : "") + ": " + added_effects(in.r);
  for (const auto& row : s.table) {
    page.table.emplace_back();
    for (const std::string& cell : row) page.table.back().push_back(fit::plplot_escape(cell));
  }
  for (const std::string& f : s.findings) page.paragraphs.push_back(fit::plplot_escape(f));
  for (const std::string& n : s.notes) page.notes.push_back(fit::plplot_escape(n));
  return page;
}

void check(const DiscrepancyResult& r, const ReportOptions& opt) {
  const ResidualTrace& tr = r.trace;
  const std::size_t n = tr.size();
  if (n == 0) throw std::invalid_argument(std::string(kWho) + "the result has no residual trace");
  for (const std::size_t m : {tr.theta.size(), tr.omega.size(), tr.torque.size(), tr.before.size(),
                              tr.after.size(), tr.heldout.size()})
    if (m != n)
      throw std::invalid_argument(std::string(kWho) + "trace columns differ in length (" +
                                  std::to_string(m) + " vs " + std::to_string(n) + ")");
  if (opt.width_px < 200 || opt.height_px < 200 || opt.width_px > 16384 || opt.height_px > 16384)
    throw std::invalid_argument(std::string(kWho) + "image size outside 200…16384 px");
  if (opt.max_points == 0) throw std::invalid_argument(std::string(kWho) + "max_points must be positive");
}

}  // namespace

std::vector<fs::path> write_discrepancy_report(const fs::path& dir, const fit::FitData& data,
                                               const DiscrepancyResult& r,
                                               const ReportOptions& opt) {
  check(r, opt);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw std::runtime_error(std::string(kWho) + "cannot create directory " + dir.string() + ": " +
                             (ec ? ec.message() : std::string("not a directory")));

  const Inputs in{r, opt, residual_figures(r.trace, r.trace.before),
                  residual_figures(r.trace, r.trace.after)};
  const detail::SummaryText text = detail::summary_text(data, r, in.before, in.after);
  const std::pair<const char*, Page> pages[] = {
      {"residual_position", residual_page(in, r.trace.theta, "position", "position θ (rad)")},
      {"residual_velocity", residual_page(in, r.trace.omega, "velocity", "velocity ω (rad/s)")},
      {"residual_time", residual_page(in, r.trace.t, "time", "time (s)")},
      {"whiteness", whiteness_page(in)},
      {"summary", summary_page(in, text)},
  };

  std::vector<fs::path> written;
  {
    const std::lock_guard<std::mutex> lock(fit::plplot_mutex());
    const std::size_t files = 2 * std::size(pages) + 1;  // and summary.md
    for (const auto& [stem, page] : pages) {
      for (const bool svg : {false, true}) {
        opt.hooks.report("drawing the report", written.size(), files);
        opt.hooks.check();
        const fs::path file = dir / (std::string(stem) + (svg ? ".svg" : ".png"));
        fit::write_plot_file(file, svg, [&](const fs::path& tmp) {
          plot::render(page, tmp, svg, opt.width_px, opt.height_px);
        });
        written.push_back(file);
      }
    }
  }
  const fs::path md = dir / "summary.md";
  try {
    interchange::write_file_atomically(md, detail::summary_markdown(opt.title, text));
  } catch (const std::system_error& e) {
    throw std::runtime_error(std::string(kWho) + e.what());
  }
  written.push_back(md);
  return written;
}

}  // namespace knoblab::discovery
