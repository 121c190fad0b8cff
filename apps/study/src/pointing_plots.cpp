// The pointing report's figures (pointing_plots.hpp) as apps/fit plot
// figures. The renderings are categories, which the plot module's numeric
// axes show as their numbers 1 … k; the axis label names them.
#include "knoblab/study/pointing_plots.hpp"

#include <algorithm>
#include <format>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "level_plot.hpp"
#include "pointing_tables.hpp"

namespace knoblab::study {

namespace {

namespace plot = fit::plot;
using plot::Mark;
using plot::Panel;
using level_plot::colour;
using level_plot::p_short;
using level_plot::series;

std::vector<std::string> rendering_names(const PointingReport& r) {
  std::vector<std::string> out;
  for (const PointingRendering& g : r.renderings) out.push_back(g.rendering);
  return out;
}

// Per rendering: the participants' values and their mean with its interval.
Panel per_rendering(const PointingReport& r, const std::vector<std::vector<double>>& values,
                    const ParticipantMean PointingRendering::*summary) {
  std::vector<ParticipantMean> means;
  for (const PointingRendering& g : r.renderings) means.push_back(g.*summary);
  return level_plot::per_level("rendering", rendering_names(r), values, means);
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
      v.movement_time[j].push_back(mean(t.times[i][j]));
      v.rating[j].push_back(mean(t.ratings[i][j]));
    }
  }
  return v;
}

plot::Figure movement_time_figure(const PointingReport& r, const ParticipantValues& v) {
  plot::Figure f;
  f.title = "Movement time per rendering";
  f.subtitle = std::format(
      "Grey: each participant's mean movement time (N = {}); colour: their mean with its 95 % confidence interval",
      r.participants.size());
  Panel p = per_rendering(r, v.movement_time, &PointingRendering::movement_time_by_participant);
  p.name = "movement_time";
  const stats::RmAnovaResult& a = r.anova_movement_time;
  p.heading = std::format("Repeated-measures ANOVA: F({}, {}) = {:.2f}, p = {}; Huynh–Feldt ε = {:.3f}, p = {}; "
                          "partial η² = {:.3f}",
                          a.df1, a.df2, a.f, p_short(a.p), a.epsilon_hf, p_short(a.p_hf), a.partial_eta_squared);
  p.ylabel = "movement time (s)";
  f.panels.push_back(std::move(p));
  f.x_column = "rendering_number";
  f.y_column = "movement_time_s";
  return f;
}

plot::Figure rating_figure(const PointingReport& r, const ParticipantValues& v) {
  plot::Figure f;
  f.title = "Rating per rendering";
  f.subtitle = std::format(
      "Grey: each participant's mean rating (N = {}); colour: their mean with its 95 % confidence interval",
      r.participants.size());
  Panel p = per_rendering(r, v.rating, &PointingRendering::rating_by_participant);
  p.name = "rating";
  if (r.friedman_rating)
    p.heading = std::format("Friedman test on the participants' medians: χ²({}) = {:.2f}, p = {}",
                            r.friedman_rating->df, r.friedman_rating->statistic, p_short(r.friedman_rating->p));
  else
    p.heading = "Participants' ratings (no Friedman test: see the report's notes)";
  p.ylabel = "rating";
  f.panels.push_back(std::move(p));
  f.x_column = "rendering_number";
  f.y_column = "rating";
  return f;
}

plot::Figure fitts_figure(const PointingReport& r) {
  plot::Figure f;
  f.title = "Movement time against effective index of difficulty";
  f.subtitle = "Each amplitude × width cell's mean movement time against ID#de#u = log#d2#u(A/W#de#u + 1), "
               "W#de#u = 4.133·SD of its end points; lines: least squares through a rendering's cells";
  const std::vector<std::string> levels = rendering_names(r), stems = level_plot::stems(levels);
  Panel p;
  p.name = "fitts";
  p.xlabel = "ID#de#u (bits)";
  p.ylabel = "movement time (s)";
  for (std::size_t j = 0; j < r.renderings.size(); ++j) {
    const PointingRendering& g = r.renderings[j];
    plot::Series cells = series(stems[j] + "_cells", level_plot::numbered(levels, j), Mark::Dots, colour(j), level_plot::kCellDot);
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
      plot::Series line = series(stems[j] + "_line", level_plot::numbered(levels, j), Mark::Line, colour(j), level_plot::kLine);
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
  const ParticipantValues v = participant_values(report, rows);
  return {{"movement_time", movement_time_figure(report, v)},
          {"fitts", fitts_figure(report)},
          {"rating", rating_figure(report, v)}};
}

std::vector<std::filesystem::path> write_pointing_plots(const PointingReport& report,
                                                        std::span<const PointingRow> rows,
                                                        const std::filesystem::path& dir,
                                                        const plot::FigureOptions& figure) {
  plot::validate(figure);
  return plot::write_figures(pointing_figures(report, rows), dir, figure);
}

}  // namespace knoblab::study
