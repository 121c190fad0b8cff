#include "compare_plot.hpp"

#include <plplot.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

#include "knoblab/fit/plplot_shared.hpp"

namespace knoblab::cli {

namespace {

namespace fs = std::filesystem;

// cmap0: background, ink, A's cloud and line, B's cloud and line.
enum Color : PLINT { kWhite, kBlack, kCloudA, kLineA, kCloudB, kLineB, kColors };
constexpr PLINT kRed[kColors] = {255, 0, 150, 20, 245, 200};
constexpr PLINT kGreen[kColors] = {255, 0, 185, 70, 190, 90};
constexpr PLINT kBlue[kColors] = {255, 0, 235, 170, 140, 0};
constexpr std::size_t kMaxPoints = 20000;  // per cloud, evenly thinned
constexpr int kWidth = 1200, kHeight = 800;

struct Series {
  std::vector<PLFLT> x, y;
  PLINT color = kBlack;
  bool line = false;
};

struct Plot {
  std::string title, xlabel, ylabel;  // PLplot text (escapes: #gh θ, #gt τ)
  std::vector<Series> series;
};

// One view of a side: the raw part of its capture against x, and its model's term.
using Part = std::function<double(const model::ThesisModel<double>&, const fit::FitData&, std::size_t)>;
using Term = std::function<double(const model::ThesisModel<double>&, double)>;

Series cloud(const CompareSide& s, const std::vector<double> fit::FitData::*x, const Part& part, PLINT color) {
  Series out{{}, {}, color, false};
  if (!s.data) return out;
  const fit::FitData& d = *s.data;
  const std::size_t step = std::max<std::size_t>(1, d.size() / kMaxPoints);
  for (std::size_t i = 0; i < d.size(); i += step) {
    out.x.push_back((d.*x)[i]);
    out.y.push_back(1e3 * part(s.model, d, i));
  }
  return out;
}

Series curve(const CompareSide& s, double lo, double hi, const Term& term, PLINT color) {
  Series out{{}, {}, color, true};
  constexpr int kSteps = 2000;
  for (int k = 0; k <= kSteps; ++k) {
    const double x = lo + (hi - lo) * k / kSteps;
    out.x.push_back(x);
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

Plot view(const CompareSide& a, const CompareSide& b, const std::vector<double> fit::FitData::*x, const Part& part,
          const Term& term, std::pair<double, double> fallback) {
  const auto [lo, hi] = x_range(a, b, x, fallback);
  Plot p;
  p.series = {cloud(a, x, part, kCloudA), cloud(b, x, part, kCloudB), curve(a, lo, hi, term, kLineA),
              curve(b, lo, hi, term, kLineB)};
  return p;
}

void draw(const Plot& plot, const fs::path& file, bool svg) {
  std::FILE* fp = std::fopen(file.c_str(), "wb");
  if (fp == nullptr) throw std::runtime_error("cannot write " + file.string() + ": " + std::strerror(errno));
  PLINT previous = 0, stream = -1;
  plgstrm(&previous);
  plmkstrm(&stream);
  if (stream < 0) {
    std::fclose(fp);
    throw std::runtime_error("cannot write " + file.string() + ": no free PLplot stream");
  }
  plsdev(svg ? "svgcairo" : "pngcairo");
  plsfile(fp);  // the driver closes it at plend1
  plspage(0.0, 0.0, kWidth, kHeight, 0, 0);
  plscmap0(kRed, kGreen, kBlue, kColors);
  plinit();
  const fit::PageMetrics m = fit::begin_page(kWidth, kHeight, svg);
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Series& s : plot.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]);
        y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
      }
  if (!(x1 > x0)) x0 -= 1, x1 += 1;
  if (!(y1 > y0)) y0 -= 1, y1 += 1;
  const double pad = 0.05 * (y1 - y0);
  plcol0(kBlack);
  plvpor(0.0, 1.0, 0.0, 1.0);  // the whole page, for the title
  plwind(0.0, 1.0, 0.0, 1.0);
  fit::page_text(1.5, 1.2, m, plot.title);
  plvpor(0.1, 0.95, 0.1, 0.86);
  plwind(x0, x1, y0 - pad, y1 + pad);
  plwidth(m.pen);
  plbox("bcnstg", 0.0, 0, "bcnstgv", 0.0, 0);
  plmtex("b", 2.7, 0.5, 0.5, plot.xlabel.c_str());
  plmtex("l", 4.0, 0.5, 0.5, plot.ylabel.c_str());
  for (const Series& s : plot.series) {
    if (s.x.empty()) continue;
    plcol0(s.color);
    plwidth((s.line ? 2.5 : 2.0) * m.pen);
    if (s.line) plline(static_cast<PLINT>(s.x.size()), s.x.data(), s.y.data());
    else plpoin(static_cast<PLINT>(s.x.size()), s.x.data(), s.y.data(), -1);  // round-capped dots
  }
  plend1();
  plsstrm(previous);
}

}  // namespace

std::vector<fs::path> write_compare_plots(const fs::path& dir, const CompareSide& a, const CompareSide& b) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create " + dir.string() + ": " + ec.message());
  const std::string who =
      fit::plplot_escape("A (blue): " + a.label + ", " + a.origin + "; B (orange): " + b.label + ", " + b.origin);
  Plot position = view(
      a, b, &fit::FitData::theta,
      [](const model::ThesisModel<double>& m, const fit::FitData& d, std::size_t i) {
        return d.torque[i] - m.inertia.torque(d.alpha[i]) - m.friction.torque(d.omega[i]);
      },
      [](const model::ThesisModel<double>& m, double theta) { return m.detents.torque(theta); },
      {-std::numbers::pi, std::numbers::pi});
  position.title = "Position torque (detents): " + who;
  position.xlabel = "position #gh (rad)";
  position.ylabel = "#gt#dpos#u (mN·m)";
  Plot velocity = view(
      a, b, &fit::FitData::omega,
      [](const model::ThesisModel<double>& m, const fit::FitData& d, std::size_t i) {
        return d.torque[i] - m.inertia.torque(d.alpha[i]) - m.detents.torque(d.theta[i]);
      },
      [](const model::ThesisModel<double>& m, double omega) { return m.friction.torque(omega); },
      {-10.0, 10.0});
  velocity.title = "Velocity torque (friction): " + who;
  velocity.xlabel = "velocity #gh\u0307 (rad/s)";
  velocity.ylabel = "#gt#dvel#u (mN·m)";

  std::vector<fs::path> files;
  std::lock_guard lock(fit::plplot_mutex());
  for (const auto& [name, plot] : {std::pair{"torque_position", &position}, std::pair{"torque_velocity", &velocity}}) {
    for (const bool svg : {false, true}) {
      const fs::path file = dir / (std::string(name) + (svg ? ".svg" : ".png"));
      fit::write_plot_file(file, svg, [&](const fs::path& temporary) { draw(*plot, temporary, svg); });
      files.push_back(file);
    }
  }
  return files;
}

}  // namespace knoblab::cli
