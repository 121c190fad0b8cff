// The pointing report's figures (pointing_plots.hpp) as apps/fit plot
// figures. The renderings are categories, which the plot module's numeric
// axes show as their numbers 1 … k; the axis label names them.
#include "knoblab/study/pointing_plots.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "knoblab/fit/plot/text.hpp"
#include "pointing_tables.hpp"

namespace knoblab::study {

namespace {

namespace plot = fit::plot;
using plot::Mark;
using plot::Panel;
using plot::Series;

// matplotlib's tab10 without its grey, which the participants' dots use.
plot::Rgb colour(std::size_t j) {
  static constexpr plot::Rgb kTab[] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},  {214, 39, 40}, {148, 103, 189},
                                       {140, 86, 75},   {227, 119, 194}, {188, 189, 34}, {23, 190, 207}};
  return kTab[j % std::size(kTab)];
}

constexpr double kMeanDot = 1.6, kCellDot = 1.2, kBar = 0.35, kLine = 0.35, kParticipantDot = 0.8;
// The participants' dots spread over ±this around their rendering's x.
constexpr double kSpread = 0.2;

// A series name for the CSV: lower_snake_case, unique in the figure.
std::vector<std::string> series_stems(const PointingReport& r) {
  std::vector<std::string> out;
  std::set<std::string> used;
  for (const PointingRendering& g : r.renderings) {
    std::string s;
    for (const char c : g.rendering) {
      const bool alnum = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
      s += alnum ? c : (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : '_';
    }
    if (s.empty() || (s[0] >= '0' && s[0] <= '9')) s = "r" + s;
    std::string unique = s;
    for (int k = 2; used.contains(unique); ++k) unique = s + "_" + std::to_string(k);
    used.insert(unique);
    out.push_back(unique);
  }
  return out;
}

std::string numbered(const PointingReport& r, std::size_t j) {
  return std::to_string(j + 1) + " " + plot::escape(r.renderings[j].rendering);
}

std::string rendering_axis(const PointingReport& r) {
  std::string s = "rendering:";
  for (std::size_t j = 0; j < r.renderings.size(); ++j) s += (j ? ", " : " ") + numbered(r, j);
  return s;
}

std::string p_text(double p) { return p >= 0.001 ? std::format("{:.3f}", p) : std::format("{:.1e}", p); }

Series series(std::string name, std::string label, Mark mark, plot::Rgb c, double size) {
  Series s;
  s.name = std::move(name);
  s.label = std::move(label);
  s.mark = mark;
  s.color = c;
  s.size_mm = size;
  return s;
}

// Per rendering: the participants' values (grey, spread around x = j + 1)
// and their mean with its interval, in the rendering's colour.
Panel per_rendering(const PointingReport& r, const std::vector<std::string>& stems,
                    const std::vector<std::vector<double>>& values,
                    const ParticipantMean PointingRendering::*summary) {
  Panel p;
  Series dots = series("participants", "", Mark::Dots, plot::palette::kRaw, kParticipantDot);
  for (std::size_t j = 0; j < values.size(); ++j) {
    const std::size_t n = values[j].size();
    for (std::size_t i = 0; i < n; ++i) {
      const double offset = n > 1 ? -kSpread + 2 * kSpread * static_cast<double>(i) / static_cast<double>(n - 1) : 0.0;
      dots.x.push_back(static_cast<double>(j + 1) + offset);
      dots.y.push_back(values[j][i]);
    }
  }
  p.series.push_back(std::move(dots));
  for (std::size_t j = 0; j < r.renderings.size(); ++j) {
    const ParticipantMean& m = r.renderings[j].*summary;
    const double x = static_cast<double>(j + 1);
    Series bar = series(stems[j] + "_ci95", "", Mark::Line, colour(j), kBar);
    bar.x = {x, x};
    bar.y = {m.low, m.high};
    Series mean = series(stems[j] + "_mean", "", Mark::Dots, colour(j), kMeanDot);
    mean.x = {x};
    mean.y = {m.mean};
    p.series.push_back(std::move(bar));
    p.series.push_back(std::move(mean));
  }
  p.xlabel = rendering_axis(r);
  return p;
}

// The participants' values per rendering, in the report's participant order.
struct ParticipantValues {
  std::vector<std::vector<double>> movement_time, rating;  // [rendering][participant]
};

ParticipantValues participant_values(const PointingReport& r, std::span<const PointingRow> rows) {
  PointingReportOptions order;
  for (const PointingRendering& g : r.renderings) order.rendering_order.push_back(g.rendering);
  const detail::PointingTables t = detail::tabulate(rows, order);
  ParticipantValues v;
  v.movement_time.resize(r.renderings.size());
  v.rating.resize(r.renderings.size());
  for (const std::string& code : r.participants) {
    const auto it = std::find(t.participants.begin(), t.participants.end(), code);
    if (it == t.participants.end())
      throw std::invalid_argument("pointing figures: participant " + code + " of the report has no rows");
    const auto i = static_cast<std::size_t>(it - t.participants.begin());
    for (std::size_t j = 0; j < r.renderings.size(); ++j) {
      if (t.times[i][j].empty())
        throw std::invalid_argument("pointing figures: participant " + code + " has no rows with rendering \"" +
                                    r.renderings[j].rendering + "\"");
      v.movement_time[j].push_back(detail::mean(t.times[i][j]));
      v.rating[j].push_back(detail::mean(t.ratings[i][j]));
    }
  }
  return v;
}

plot::Figure movement_time_figure(const PointingReport& r, const std::vector<std::string>& stems,
                                  const ParticipantValues& v) {
  plot::Figure f;
  f.title = "Movement time per rendering";
  f.subtitle = std::format(
      "Grey: each participant's mean movement time (N = {}); colour: their mean with its 95 % confidence interval",
      r.participants.size());
  Panel p = per_rendering(r, stems, v.movement_time, &PointingRendering::movement_time_by_participant);
  p.name = "movement_time";
  const stats::RmAnovaResult& a = r.anova_movement_time;
  p.heading = std::format("Repeated-measures ANOVA: F({}, {}) = {:.2f}, p = {}; Huynh–Feldt ε = {:.3f}, p = {}; "
                          "partial η² = {:.3f}",
                          a.df1, a.df2, a.f, p_text(a.p), a.epsilon_hf, p_text(a.p_hf), a.partial_eta_squared);
  p.ylabel = "movement time (s)";
  f.panels.push_back(std::move(p));
  f.x_column = "rendering_number";
  f.y_column = "movement_time_s";
  return f;
}

plot::Figure rating_figure(const PointingReport& r, const std::vector<std::string>& stems, const ParticipantValues& v) {
  plot::Figure f;
  f.title = "Rating per rendering";
  f.subtitle = std::format(
      "Grey: each participant's mean rating (N = {}); colour: their mean with its 95 % confidence interval",
      r.participants.size());
  Panel p = per_rendering(r, stems, v.rating, &PointingRendering::rating_by_participant);
  p.name = "rating";
  if (r.friedman_rating)
    p.heading = std::format("Friedman test on the participants' medians: χ²({}) = {:.2f}, p = {}",
                            r.friedman_rating->df, r.friedman_rating->statistic, p_text(r.friedman_rating->p));
  else
    p.heading = "Participants' ratings (no Friedman test: see the report's notes)";
  p.ylabel = "rating";
  f.panels.push_back(std::move(p));
  f.x_column = "rendering_number";
  f.y_column = "rating";
  return f;
}

plot::Figure fitts_figure(const PointingReport& r, const std::vector<std::string>& stems) {
  plot::Figure f;
  f.title = "Movement time against effective index of difficulty";
  f.subtitle = "Each amplitude × width cell's mean movement time against ID#de#u = log#d2#u(A/W#de#u + 1), "
               "W#de#u = 4.133·SD of its end points; lines: least squares through a rendering's cells";
  Panel p;
  p.name = "fitts";
  p.xlabel = "ID#de#u (bits)";
  p.ylabel = "movement time (s)";
  for (std::size_t j = 0; j < r.renderings.size(); ++j) {
    const PointingRendering& g = r.renderings[j];
    Series cells = series(stems[j] + "_cells", numbered(r, j), Mark::Dots, colour(j), kCellDot);
    cells.legend_rank = static_cast<int>(j);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const PointingCell& c : g.cells) {
      cells.x.push_back(c.IDe_bits);
      cells.y.push_back(c.movement_time_s);
      lo = std::min(lo, c.IDe_bits);
      hi = std::max(hi, c.IDe_bits);
    }
    p.series.push_back(std::move(cells));
    if (g.fitts_line) {
      Series line = series(stems[j] + "_line", numbered(r, j), Mark::Line, colour(j), kLine);
      line.legend_rank = static_cast<int>(j);
      line.x = {lo, hi};
      line.y = {g.fitts_line->intercept + g.fitts_line->slope * lo, g.fitts_line->intercept + g.fitts_line->slope * hi};
      p.series.push_back(std::move(line));
    }
  }
  f.panels.push_back(std::move(p));
  f.x_column = "IDe_bits";
  f.y_column = "movement_time_s";
  return f;
}

}  // namespace

std::vector<plot::NamedFigure> pointing_figures(const PointingReport& report, std::span<const PointingRow> rows) {
  if (report.renderings.empty()) throw std::invalid_argument("pointing figures: the report has no renderings");
  const std::vector<std::string> stems = series_stems(report);
  const ParticipantValues v = participant_values(report, rows);
  return {{"movement_time", movement_time_figure(report, stems, v)},
          {"fitts", fitts_figure(report, stems)},
          {"rating", rating_figure(report, stems, v)}};
}

std::vector<std::filesystem::path> write_pointing_plots(const PointingReport& report,
                                                        std::span<const PointingRow> rows,
                                                        const std::filesystem::path& dir,
                                                        const plot::FigureOptions& figure) {
  plot::validate(figure);
  return plot::write_figures(pointing_figures(report, rows), dir, figure);
}

}  // namespace knoblab::study
