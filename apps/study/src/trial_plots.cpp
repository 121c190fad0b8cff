// The per-trial report's figures (trial_plots.hpp), from the participants'
// values the report keeps per level.
#include "knoblab/study/trial_plots.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <stdexcept>
#include <string>
#include <utility>

#include "level_plot.hpp"

namespace knoblab::study {

namespace {

namespace plot = fit::plot;

plot::Figure rating_figure(const TrialReport& r, const ScaleTests& st) {
  std::vector<std::string> levels;
  std::vector<std::vector<double>> values;
  std::vector<ParticipantMean> means;
  for (const LevelSummary& l : r.levels) {
    const auto v = l.rating_values.find(st.scale);
    if (v == l.rating_values.end()) continue;
    levels.push_back(l.level);
    values.push_back(v->second);
    means.push_back(l.rating_by_participant.at(st.scale));
  }
  plot::Figure f;
  f.title = st.scale + " per " + r.factor;
  f.subtitle = std::format("Grey: each participant's mean (N = {}); colour: their mean with its 95 % confidence interval",
                           r.participants.size());
  plot::Panel p = level_plot::per_level(r.factor, levels, values, means);
  p.name = "rating";
  p.heading = st.tests.friedman ? std::format("Friedman χ²({}) = {:.2f}, p = {}", st.tests.friedman->df,
                                              st.tests.friedman->statistic, level_plot::p_short(st.tests.friedman->p))
                                : std::string("no Friedman test: see the report's notes");
  p.ylabel = st.scale;
  f.panels.push_back(std::move(p));
  f.x_column = r.factor + "_number";
  f.y_column = st.scale;
  return f;
}

// Matched / reference per knob: 1 is a perfect match.
plot::Figure match_figure(const TrialReport& r, const std::string& parameter) {
  std::vector<std::string> levels;
  std::vector<std::vector<double>> values;
  std::vector<ParticipantMean> means;
  for (const MatchEstimate& m : r.matches) {
    if (m.parameter != parameter || !std::isfinite(m.ratio)) continue;
    const LevelSummary* l = nullptr;
    for (const LevelSummary& s : r.levels)
      if (s.level == m.level) l = &s;
    std::vector<double> v = l->measure_values.at("slider_" + parameter);
    for (double& x : v) x /= m.reference;
    ParticipantMean scaled = m.matched;
    scaled.mean /= m.reference;
    scaled.low /= m.reference;
    scaled.high /= m.reference;
    if (scaled.low > scaled.high) std::swap(scaled.low, scaled.high);
    levels.push_back(m.level);
    values.push_back(std::move(v));
    means.push_back(scaled);
  }
  plot::Figure f;
  f.title = parameter + " matched against the reference knobs";
  f.subtitle = std::format("Each participant's mean setting over the knob's own value (grey, N = {}); colour: their "
                           "mean with its 95 % confidence interval; 1: a perfect match",
                           r.participants.size());
  plot::Panel p = level_plot::per_level("knob", levels, values, means);
  plot::Series one = level_plot::series("perfect_match", "", plot::Mark::Line, plot::palette::kRaw, level_plot::kLine);
  one.x = {0.5, static_cast<double>(levels.size()) + 0.5};
  one.y = {1.0, 1.0};
  p.series.insert(p.series.begin(), std::move(one));
  p.name = "match";
  p.ylabel = "matched / reference";
  p.y_from_zero = true;
  f.panels.push_back(std::move(p));
  f.x_column = "knob_number";
  f.y_column = "ratio";
  return f;
}

}  // namespace

std::vector<plot::NamedFigure> trial_figures(const TrialReport& report) {
  if (report.levels.empty()) throw std::invalid_argument("study figures: the report has no levels");
  std::vector<plot::NamedFigure> out;
  for (const ScaleTests& st : report.scales) out.push_back({"rating_" + st.scale, rating_figure(report, st)});
  std::vector<std::string> parameters;
  for (const MatchEstimate& m : report.matches)
    if (std::isfinite(m.ratio) && std::find(parameters.begin(), parameters.end(), m.parameter) == parameters.end())
      parameters.push_back(m.parameter);
  for (const std::string& p : parameters) out.push_back({"match_" + p, match_figure(report, p)});
  return out;
}

std::vector<std::filesystem::path> write_trial_plots(const TrialReport& report, const std::filesystem::path& dir,
                                                     const plot::FigureOptions& figure) {
  plot::validate(figure);
  return plot::write_figures(trial_figures(report), dir, figure);
}

}  // namespace knoblab::study
