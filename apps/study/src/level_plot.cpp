#include "level_plot.hpp"

#include <format>
#include <set>
#include <utility>

#include "knoblab/fit/plot/text.hpp"

namespace knoblab::study::level_plot {

namespace plot = fit::plot;

namespace {

// The participants' dots spread over ±this around their level's x.
constexpr double kSpread = 0.2;

}  // namespace

plot::Rgb colour(std::size_t j) {
  static constexpr plot::Rgb kTab[] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},  {214, 39, 40}, {148, 103, 189},
                                       {140, 86, 75},   {227, 119, 194}, {188, 189, 34}, {23, 190, 207}};
  return kTab[j % std::size(kTab)];
}

std::vector<std::string> stems(std::span<const std::string> levels) {
  std::vector<std::string> out;
  std::set<std::string> used;
  for (const std::string& level : levels) {
    std::string s;
    for (const char c : level) {
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

std::string numbered(std::span<const std::string> levels, std::size_t j) {
  return std::to_string(j + 1) + " " + plot::escape(levels[j]);
}

std::string axis(const std::string& word, std::span<const std::string> levels) {
  std::string s = word + ":";
  for (std::size_t j = 0; j < levels.size(); ++j) s += (j ? ", " : " ") + numbered(levels, j);
  return s;
}

std::string p_short(double p) { return p >= 0.001 ? std::format("{:.3f}", p) : std::format("{:.1e}", p); }

plot::Series series(std::string name, std::string label, plot::Mark mark, plot::Rgb c, double size) {
  plot::Series s;
  s.name = std::move(name);
  s.label = std::move(label);
  s.mark = mark;
  s.color = c;
  s.size_mm = size;
  return s;
}

plot::Panel per_level(const std::string& word, std::span<const std::string> levels,
                      const std::vector<std::vector<double>>& values, const std::vector<ParticipantMean>& means) {
  const std::vector<std::string> names = stems(levels);
  plot::Panel p;
  plot::Series dots = series("participants", "", plot::Mark::Dots, plot::palette::kRaw, kParticipantDot);
  for (std::size_t j = 0; j < values.size(); ++j) {
    const std::size_t n = values[j].size();
    for (std::size_t i = 0; i < n; ++i) {
      const double offset = n > 1 ? -kSpread + 2 * kSpread * static_cast<double>(i) / static_cast<double>(n - 1) : 0.0;
      dots.x.push_back(static_cast<double>(j + 1) + offset);
      dots.y.push_back(values[j][i]);
    }
  }
  p.series.push_back(std::move(dots));
  for (std::size_t j = 0; j < means.size(); ++j) {
    const ParticipantMean& m = means[j];
    const double x = static_cast<double>(j + 1);
    plot::Series bar = series(names[j] + "_ci95", "", plot::Mark::Line, colour(j), kBar);
    bar.x = {x, x};
    bar.y = {m.low, m.high};
    plot::Series mean = series(names[j] + "_mean", "", plot::Mark::Dots, colour(j), kMeanDot);
    mean.x = {x};
    mean.y = {m.mean};
    p.series.push_back(std::move(bar));
    p.series.push_back(std::move(mean));
  }
  p.xlabel = axis(word, levels);
  return p;
}

}  // namespace knoblab::study::level_plot
