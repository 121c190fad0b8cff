// The pieces every per-level study figure is drawn from (apps/fit's plot
// module): a colour per level, the levels numbered on the x axis and named
// in its label, and the participants' values (grey) with their mean and
// 95 % interval per level. Shared by the pointing and the per-trial figures.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "knoblab/fit/plot/figure.hpp"
#include "knoblab/study/level_tests.hpp"

namespace knoblab::study::level_plot {

// matplotlib's tab10 without its grey, which the participants' dots use.
fit::plot::Rgb colour(std::size_t j);

inline constexpr double kMeanDot = 1.6, kCellDot = 1.2, kBar = 0.35, kLine = 0.35, kParticipantDot = 0.8;

// Series names for the CSV: lower_snake_case, unique in the figure.
std::vector<std::string> stems(std::span<const std::string> levels);
// "3 high-friction": the level's number on the axis and its name.
std::string numbered(std::span<const std::string> levels, std::size_t j);
// "rendering: 1 not-rendered, 2 low-friction, …"
std::string axis(const std::string& word, std::span<const std::string> levels);
// p short enough for a heading: 0.012, 3.4e-05.
std::string p_short(double p);

fit::plot::Series series(std::string name, std::string label, fit::plot::Mark mark, fit::plot::Rgb c, double size);

// Per level: values[level][participant] as grey dots spread around x = j + 1,
// and means[level] as a dot with its interval, in the level's colour.
fit::plot::Panel per_level(const std::string& word, std::span<const std::string> levels,
                           const std::vector<std::vector<double>>& values, const std::vector<ParticipantMean>& means);

}  // namespace knoblab::study::level_plot
