#include "compare_plot.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "knoblab/fit/plot/figure_files.hpp"
#include "knoblab/fit/plot/text.hpp"

namespace knoblab::cli {

namespace {

namespace fs = std::filesystem;
namespace plot = fit::plot;

constexpr std::size_t kMaxPoints = 20000;  // per cloud, evenly thinned
constexpr double kDeg = 180.0 / std::numbers::pi;
// A blue, B orange (matplotlib's tab10); each cloud a light tint of its line.
constexpr plot::Rgb kCloudA{150, 185, 235}, kCloudB{245, 190, 140};

// One view of a side: the raw part of its capture against x, and its model's term.
using Part = std::function<double(const model::ThesisModel<double>&, const fit::FitData&, std::size_t)>;
using Term = std::function<double(const model::ThesisModel<double>&, double)>;

plot::Series cloud(const CompareSide& s, const std::string& name, const std::vector<double> fit::FitData::*x,
                   const Part& part, plot::Rgb color) {
  plot::Series out;
  out.name = name;
  out.label = s.data ? (name.substr(0, 1) == "a" ? "A data" : "B data") : "";
  out.mark = plot::Mark::Dots;
  out.color = color;
  out.size_mm = 0.3;
  if (!s.data) return out;
  const fit::FitData& d = *s.data;
  const std::size_t step = std::max<std::size_t>(1, d.size() / kMaxPoints);
  for (std::size_t i = 0; i < d.size(); i += step) {
    out.x.push_back(kDeg * (d.*x)[i]);
    out.y.push_back(1e3 * part(s.model, d, i));
  }
  return out;
}

plot::Series curve(const CompareSide& s, const std::string& name, const std::string& label, double lo, double hi,
                   const Term& term, plot::Rgb color) {
  plot::Series out;
  out.name = name;
  out.label = label;
  out.mark = plot::Mark::Line;
  out.color = color;
  out.size_mm = 0.5;
  constexpr int kSteps = 2000;
  for (int k = 0; k <= kSteps; ++k) {
    const double x = lo + (hi - lo) * k / kSteps;
    out.x.push_back(kDeg * x);
    out.y.push_back(1e3 * term(s.model, x));
  }
  return out;
}

// Where x goes in the captures' data (central 99.8 %), or `fallback`.
std::pair<double, double> x_range(const CompareSide& a, const CompareSide& b, const std::vector<double> fit::FitData::*x,
                                  std::pair<double, double> fallback) {
  std::vector<double> v;
  for (const CompareSide* s : {&a, &b})
    if (s->data) v.insert(v.end(), ((*s->data).*x).begin(), ((*s->data).*x).end());
  if (v.size() < 2) return fallback;
  std::sort(v.begin(), v.end());
  const auto at = [&](double q) { return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))]; };
  return {at(0.001), at(0.999)};
}

plot::Figure view(const CompareSide& a, const CompareSide& b, const std::vector<double> fit::FitData::*x,
                  const Part& part, const Term& term, std::pair<double, double> fallback) {
  const auto [lo, hi] = x_range(a, b, x, fallback);
  plot::Panel p;
  p.name = "overlay";
  // Raw data first, under both models.
  p.series = {cloud(a, "a_data", x, part, kCloudA), cloud(b, "b_data", x, part, kCloudB),
              curve(a, "a_model", "A model", lo, hi, term, plot::palette::kBlue),
              curve(b, "b_model", "B model", lo, hi, term, plot::palette::kOrange)};
  plot::Figure f;
  f.subtitle = plot::escape("A: " + a.label + " (" + a.origin + ");  B: " + b.label + " (" + b.origin + ")");
  f.panels = {std::move(p)};
  f.y_column = "torque_mNm";
  return f;
}

}  // namespace

std::vector<fs::path> write_compare_plots(const fs::path& dir, const CompareSide& a, const CompareSide& b,
                                          const fit::plot::FigureOptions& options) {
  plot::Figure position = view(
      a, b, &fit::FitData::theta,
      [](const model::ThesisModel<double>& m, const fit::FitData& d, std::size_t i) {
        return d.torque[i] - m.inertia.torque(d.alpha[i]) - m.friction.torque(d.omega[i]);
      },
      [](const model::ThesisModel<double>& m, double theta) { return m.detents.torque(theta); },
      {-std::numbers::pi, std::numbers::pi});
  position.title = "Position torque (detents)";
  position.panels[0].xlabel = "position #gh (deg)";
  position.panels[0].ylabel = "#gt#dpos#u (mN·m)";
  position.x_column = "position_deg";
  plot::Figure velocity = view(
      a, b, &fit::FitData::omega,
      [](const model::ThesisModel<double>& m, const fit::FitData& d, std::size_t i) {
        return d.torque[i] - m.inertia.torque(d.alpha[i]) - m.detents.torque(d.theta[i]);
      },
      [](const model::ThesisModel<double>& m, double omega) { return m.friction.torque(omega); },
      {-10.0, 10.0});
  velocity.title = "Velocity torque (friction)";
  velocity.panels[0].xlabel = "velocity #gh\u0307 (deg/s)";
  velocity.panels[0].ylabel = "#gt#dvel#u (mN·m)";
  velocity.x_column = "velocity_deg_s";
  return plot::write_figures({{"torque_position", std::move(position)}, {"torque_velocity", std::move(velocity)}},
                             dir, options);
}

}  // namespace knoblab::cli
