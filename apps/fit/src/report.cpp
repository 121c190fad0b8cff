// The fit report's figures (thesis Figures 17–19 and 22–34) as plot::Figure.
//
// Raw torque is a light grey point cloud drawn first, the fit black over
// it, the 95% band of the fitted curve dashed. A band is a few hundredths of
// a mN·m on a plot spanning tens, thinner than its line, so every page also
// has a residual panel (raw − fitted) on the residuals' own scale, where the
// bands are shaded under the residuals: the curve's band dark blue, the
// observation band light blue. The total torque against θ or θ̇ is not a function of that axis (it
// depends on all of θ, θ̇, θ̈), so fitted τ is drawn as points there; the
// parts τ_pos(θ) and τ_vel(θ̇) are functions, so they are drawn as lines
// through the samples sorted by the axis. Their band half-widths come from
// the whole model's band (Prediction::curve_half, which varies with all
// three kinematic variables), averaged over neighbouring samples along the
// axis so the dashed line is a curve rather than noise.
#include "knoblab/fit/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "knoblab/fit/plot/reduce.hpp"
#include "knoblab/fit/plot/text.hpp"
#include "knoblab/model/quantile.hpp"

namespace knoblab::fit {
namespace {

namespace fs = std::filesystem;
using plot::Mark;
using plot::Panel;
using plot::Series;
namespace palette = plot::palette;


// Marker sizes and line widths, mm.
constexpr double kCloudDot = 0.4, kFitDot = 0.18, kFitLine = 0.35, kBandLine = 0.25;

struct Inputs {
  const FitResult& r;
  const FitData& d;
  const Prediction& p;
  const ReportOptions& opt;
  std::size_t n;
  bool has_obs;
  std::vector<double> theta_shown, omega_shown;  // in the axes' units: deg, deg/s (mm, mm/s)
  const AxisUnits& u;  // SI to the figures' units, at the edge only

  double torque(double si) const { return u.torque(si); }
  std::string tau() const { return std::string(u.tau); }
  std::string effort() const { return std::string(u.effort); }
  // "τ (mN·m)", "F (N)"
  std::string torque_label(const std::string& what) const {
    return what + " (" + std::string(u.torque.axis_label()) + ")";
  }
  std::string torque_column(const std::string& what) const {
    return what + "_" + std::string(u.torque.column_suffix());
  }
};

std::vector<double> scaled(const std::vector<double>& v, double k) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = k * v[i];
  return out;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

Series series(std::string name, std::string label, Mark mark, plot::Rgb color, double size, int rank) {
  Series s;
  s.name = std::move(name);
  s.label = std::move(label);
  s.mark = mark;
  s.color = color;
  s.size_mm = size;
  s.legend_rank = rank;
  return s;
}

// Points (x[i], y(i)) of the given samples.
Series points(Series s, const std::vector<double>& x, const std::vector<std::size_t>& idx, const plot::Values& y) {
  s.x.reserve(idx.size());
  s.y.reserve(idx.size());
  for (const std::size_t i : idx) {
    s.x.push_back(x[i]);
    s.y.push_back(y(i));
  }
  return s;
}

// Raw and fitted total torque against x (θ or θ̇): the top panels.
Panel total_panel(const Inputs& in, const std::vector<double>& x, const std::string& xlabel) {
  Panel panel;
  panel.name = "total";
  panel.heading = "All " + in.effort() + "s: raw " + in.tau() + " and fitted " + in.tau();
  panel.xlabel = xlabel;
  panel.ylabel = in.torque_label(in.tau());
  const auto cloud = plot::thin(in.n, in.opt.max_points);
  const auto fitted = plot::thin(in.n, std::max<std::size_t>(1, in.opt.max_points / 4));
  panel.series.push_back(points(series("raw_torque", "raw " + in.tau(), Mark::Dots, palette::kRaw, kCloudDot, 0), x,
                                cloud, [&](std::size_t i) { return in.torque(in.d.torque[i]); }));
  panel.series.push_back(points(series("fitted_torque", "fitted " + in.tau(), Mark::Dots, palette::kBlack, kFitDot, 1),
                                x, fitted, [&](std::size_t i) { return in.torque(in.p.tau[i]); }));
  return panel;
}

// One part of Eq. 6 against its own variable: raw part (the torque less the
// other fitted parts) as a cloud, the fitted part as a line with its bands.
Panel part_panel(const Inputs& in, const std::vector<double>& x, const std::vector<double>& fit,
                 const std::vector<double>& others_a, const std::vector<double>& others_b,
                 const std::string& part, const std::string& name) {
  Panel panel;
  panel.name = name + "_part";
  panel.ylabel = in.torque_label(part);
  const auto cloud = plot::thin(in.n, in.opt.max_points);
  panel.series.push_back(points(series("raw_" + name, "raw " + part, Mark::Dots, palette::kRaw, kCloudDot, 0), x,
                                cloud, [&](std::size_t i) {
                                  return in.torque(in.d.torque[i] - others_a[i] - others_b[i]);
                                }));
  // Fitted part: a line through the samples sorted by x. Bands: fewer
  // vertices, as a dashed line is dashed piece by piece.
  const auto order = plot::sorted_by(x);
  auto add_line = [&](Series s, std::size_t vertices, const std::vector<double>& halfs, double sign) {
    for (const std::size_t k : plot::thin(in.n, vertices)) {
      const std::size_t i = order[k];
      s.x.push_back(x[i]);
      s.y.push_back(in.torque(fit[i] + (halfs.empty() ? 0.0 : sign * halfs[k])));
    }
    panel.series.push_back(std::move(s));
  };
  const std::size_t band_vertices = std::min<std::size_t>(in.opt.max_points, 600);
  if (in.has_obs) {
    const auto obs = plot::smoothed_along(in.p.observation_half, order);
    const std::string label = "95% observation band";
    add_line(series("observation_band_upper", label, Mark::Dotted, palette::kBlue, kBandLine, 3), band_vertices, obs, 1.0);
    add_line(series("observation_band_lower", label, Mark::Dotted, palette::kBlue, kBandLine, 3), band_vertices, obs, -1.0);
  }
  const auto band = plot::smoothed_along(in.p.curve_half, order);
  add_line(series("band_upper", "95% band of the fit", Mark::Dashed, palette::kBlack, kBandLine, 2), band_vertices, band, 1.0);
  add_line(series("band_lower", "95% band of the fit", Mark::Dashed, palette::kBlack, kBandLine, 2), band_vertices, band, -1.0);
  add_line(series("fitted_" + name, "fitted " + part, Mark::Line, palette::kBlack, kFitLine, 1),
           std::min<std::size_t>(in.opt.max_points, 4000), {}, 0.0);
  return panel;
}

// The residual raw τ − fitted τ of every sample, N·m.
std::vector<double> residuals(const Inputs& in) {
  std::vector<double> r(in.n);
  for (std::size_t i = 0; i < in.n; ++i) r[i] = in.d.torque[i] - in.p.tau[i];
  return r;
}

double finite_quantile(const std::vector<double>& v, double q) {
  std::vector<double> f;
  f.reserve(v.size());
  for (const double x : v)
    if (std::isfinite(x)) f.push_back(x);
  return model::quantile(std::move(f), q);
}

// A residual panel's y range: six robust standard deviations of the residual
// (median absolute deviation) and the bands' usual width, so the transients
// the fit left out (stick-band samples, breakaway) do not shrink the bands to
// a line. The heading counts what lies beyond.
void fit_residual_range(Panel& panel, const Inputs& in, const std::vector<double>& r) {
  std::vector<double> dev(r.size());
  const double med = finite_quantile(r, 0.5);
  for (std::size_t i = 0; i < r.size(); ++i) dev[i] = std::abs(r[i] - med);
  double limit = 6.0 * 1.4826 * finite_quantile(dev, 0.5);
  for (const auto* half : {&in.p.curve_half, &in.p.observation_half}) {
    if (half->empty()) continue;
    const double h = finite_quantile(*half, 0.95);
    if (std::isfinite(h)) limit = std::max(limit, 1.3 * h);
  }
  if (!(limit > 0.0) || !std::isfinite(limit)) return;
  panel.y_lo = -in.torque(limit);
  panel.y_hi = in.torque(limit);
  std::size_t beyond = 0;
  for (const double v : r) beyond += std::abs(v) > limit ? 1 : 0;
  if (beyond > 0) panel.heading += " (" + std::to_string(beyond) + " beyond ±" + in.u.torque.with(limit) + ")";
}

Series zero_line(double x0, double x1) {
  Series s = series("zero", "", Mark::Line, palette::kBlack, 0.2, 0);
  s.x = {x0, x1};
  s.y = {0.0, 0.0};
  return s;
}

std::string residual_heading(const Inputs& in) {
  return "Residual raw " + in.tau() + " − fitted " + in.tau() + ", 95% bands shaded";
}

// Residual against θ or θ̇ with the shaded bands about zero (bands averaged
// along the axis, as in the part panels).
Panel residual_panel(const Inputs& in, const std::vector<double>& x, const std::string& xlabel) {
  Panel panel;
  panel.name = "residual";
  panel.heading = residual_heading(in);
  panel.xlabel = xlabel;
  panel.ylabel = in.torque_label("residual");
  const std::vector<double> r = residuals(in);
  const auto order = plot::sorted_by(x);
  const auto vertices = plot::thin(in.n, std::min<std::size_t>(in.opt.max_points, 600));
  auto fill = [&](std::string name, std::string label, plot::Rgb color, int rank, const std::vector<double>& half) {
    Series s = series(std::move(name), std::move(label), Mark::Fill, color, 0.0, rank);
    const auto smooth = plot::smoothed_along(half, order);
    for (const std::size_t k : vertices) {
      s.x.push_back(x[order[k]]);
      s.y.push_back(in.torque(smooth[k]));
      s.y_low.push_back(-in.torque(smooth[k]));
    }
    return s;
  };
  // The bands under the residuals, so every residual shows.
  if (in.has_obs)
    panel.series.push_back(fill("observation_band", "95% observation band", palette::kBandLight, 3, in.p.observation_half));
  panel.series.push_back(fill("band", "95% band of the fit", palette::kBandDark, 2, in.p.curve_half));
  panel.series.push_back(points(series("residual", "residual", Mark::Dots, palette::kRaw, kCloudDot, 0), x,
                                plot::thin(in.n, in.opt.max_points), [&](std::size_t i) { return in.torque(r[i]); }));
  panel.series.push_back(zero_line(x[order.front()], x[order.back()]));
  fit_residual_range(panel, in, r);
  return panel;
}

std::string with_title(const ReportOptions& opt, const std::string& what) {
  return opt.title.empty() ? what : plot::escape(opt.title) + " — " + what;
}

std::string summary(const FitResult& r, std::size_t n) {
  std::string s = std::string(model_name(r.model)) + " fit, " + std::to_string(n) + " samples";
  if (r.rmse_Nm > 0.0) s += ", RMSE " + units(r.axis).torque.with(r.rmse_Nm);
  if (r.fit_percent != 0.0) s += ", fit " + fmt("%.1f", r.fit_percent) + " %";
  s += r.detents ? ", detents" : ", no detents";
  return s;
}

plot::Figure page(const Inputs& in, const std::string& what, std::string x_column) {
  plot::Figure f;
  f.title = with_title(in.opt, what);
  f.subtitle = summary(in.r, in.n);
  f.x_column = std::move(x_column);
  f.y_column = in.torque_column(in.effort());
  f.y_low_column = in.torque_column(in.effort() + "_lower");
  return f;
}

plot::Figure position_figure(const Inputs& in) {
  const std::string t = in.tau();
  plot::Figure f = page(in, in.effort() + " against position", "position_" + std::string(in.u.position.column_suffix()));
  const std::string xl = "position " + std::string(in.u.theta) + " (" + std::string(in.u.position.axis_label()) + ")";
  const auto& x = in.theta_shown;
  f.panels.push_back(total_panel(in, x, xl));
  Panel part = part_panel(in, x, in.p.pos, in.p.acc, in.p.vel, t + "#dpos#u", "position");
  part.xlabel = xl;
  part.heading = "Position part: " + t + "#dpos#u = " + t + " − " + t + "#dacc#u − " + t + "#dvel#u" +
                 (in.r.detents ? "" : " (no detents fitted: fitted " + t + "#dpos#u = 0)");
  f.panels.push_back(std::move(part));
  f.panels.push_back(residual_panel(in, x, xl));
  return f;
}

plot::Figure velocity_figure(const Inputs& in) {
  const std::string t = in.tau();
  plot::Figure f = page(in, in.effort() + " against velocity", "velocity_" + std::string(in.u.plot_speed.column_suffix()));
  const std::string xl =
      "velocity " + std::string(in.u.theta_dot) + " (" + std::string(in.u.plot_speed.axis_label()) + ")";
  const auto& x = in.omega_shown;
  f.panels.push_back(total_panel(in, x, xl));
  Panel part = part_panel(in, x, in.p.vel, in.p.acc, in.p.pos, t + "#dvel#u", "velocity");
  part.xlabel = xl;
  part.heading = "Velocity part: " + t + "#dvel#u = " + t + " − " + t + "#dacc#u − " + t + "#dpos#u";
  if (in.r.stick && in.r.stick->dv > 0.0) {
    for (Panel* pn : {&f.panels.front(), &part}) {
      Series limits = series("stick_band_limit", "stick band ±Δv", Mark::VLines, palette::kOrange, 0.3, 4);
      limits.x = {-in.u.plot_speed(in.r.stick->dv), in.u.plot_speed(in.r.stick->dv)};
      pn->series.push_back(std::move(limits));
    }
  }
  f.panels.push_back(std::move(part));
  f.panels.push_back(residual_panel(in, x, xl));
  return f;
}

plot::Figure time_figure(const Inputs& in) {
  plot::Figure f = page(in, in.effort() + " against time", "time_s");
  const auto& d = in.d;
  const auto& p = in.p;
  const auto cloud = plot::thin(in.n, in.opt.max_points);
  const std::size_t line_buckets = std::max<std::size_t>(1, in.opt.max_points / 2);
  const std::size_t band_buckets = std::min<std::size_t>(in.opt.max_points, 1000);

  Panel top;
  top.name = "total";
  top.heading = "Raw and fitted " + in.effort();
  top.xlabel = "time (s)";
  top.ylabel = in.torque_label(in.tau());
  top.series.push_back(points(series("raw_torque", "raw " + in.tau(), Mark::Dots, palette::kRaw, kCloudDot, 0), d.t,
                              cloud, [&](std::size_t i) { return in.torque(d.torque[i]); }));
  Series fitted = series("fitted_torque", "fitted " + in.tau(), Mark::Line, palette::kBlack, 0.2, 1);
  plot::minmax_series(fitted, d.t, line_buckets, [&](std::size_t i) { return in.torque(p.tau[i]); });
  top.series.push_back(std::move(fitted));

  Panel bottom;
  bottom.name = "residual";
  bottom.heading = residual_heading(in);
  bottom.xlabel = "time (s)";
  bottom.ylabel = in.torque_label("residual");
  // Shaded ±h(t), h's largest value over each bucket.
  auto band = [&](std::string name, std::string label, plot::Rgb color, int rank, const std::vector<double>& half) {
    Series s = series(std::move(name), std::move(label), Mark::Fill, color, 0.0, rank);
    plot::envelope_series(s, d.t, band_buckets, [&](std::size_t i) { return in.torque(half[i]); });
    for (const double y : s.y) s.y_low.push_back(-y);
    bottom.series.push_back(std::move(s));
  };
  const std::vector<double> r = residuals(in);
  if (in.has_obs) band("observation_band", "95% observation band", palette::kBandLight, 3, p.observation_half);
  band("band", "95% band of the fit", palette::kBandDark, 2, p.curve_half);
  bottom.series.push_back(points(series("residual", "residual", Mark::Dots, palette::kRaw, kCloudDot, 0), d.t, cloud,
                                 [&](std::size_t i) { return in.torque(r[i]); }));
  bottom.series.push_back(zero_line(d.t.front(), d.t.back()));
  fit_residual_range(bottom, in, r);

  f.panels.push_back(std::move(top));
  f.panels.push_back(std::move(bottom));
  return f;
}

plot::Figure ci_figure(const Inputs& in) {
  plot::Figure f = page(in, "95% confidence band of the fitted " + in.effort(),
                        in.torque_column("fitted_" + in.effort()));
  f.y_column = in.torque_column("half_width");
  Panel panel;
  panel.name = "band";
  panel.heading = "Half-width of the fitted curve's 95% band against fitted " + in.effort();
  panel.xlabel = in.torque_label("fitted " + in.tau());
  panel.ylabel = in.torque_label("95% band half-width");
  panel.y_from_zero = true;
  Series pts = series("per_sample", "per sample", Mark::Dots, palette::kBlack, 0.3, 0);
  for (const std::size_t i : plot::thin(in.n, in.opt.max_points)) {
    pts.x.push_back(in.torque(in.p.tau[i]));
    pts.y.push_back(in.torque(in.p.curve_half[i]));
  }
  double sum = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::size_t finite = 0;
  for (const double h : in.p.curve_half) {
    if (!std::isfinite(h)) continue;
    sum += h;
    ++finite;
  }
  for (const double v : pts.x)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  panel.series.push_back(std::move(pts));
  if (finite > 0 && lo <= hi) {
    const double mean = in.torque(sum / static_cast<double>(finite));
    Series avg = series("mean", "mean " + fmt("%.3g", mean) + " " + std::string(in.u.torque.text), Mark::Dashed,
                        palette::kRed, 0.3, 1);
    avg.x = {lo, hi};
    avg.y = {mean, mean};
    panel.series.push_back(std::move(avg));
  }
  f.panels.push_back(std::move(panel));
  return f;
}

void check_inputs(const FitData& data, const Prediction& p, const ReportOptions& opt) {
  const std::size_t n = data.size();
  auto need = [&](std::size_t size, const char* what) {
    if (size != n)
      throw std::invalid_argument(std::string("knoblab::fit::write_report: ") + what + " has " +
                                  std::to_string(size) + " values, the data " + std::to_string(n));
  };
  if (n == 0) throw std::invalid_argument("knoblab::fit::write_report: no samples");
  need(data.theta.size(), "data.theta");
  need(data.omega.size(), "data.omega");
  need(data.alpha.size(), "data.alpha");
  need(data.torque.size(), "data.torque");
  need(p.tau.size(), "prediction.tau");
  need(p.acc.size(), "prediction.acc");
  need(p.vel.size(), "prediction.vel");
  need(p.pos.size(), "prediction.pos");
  need(p.curve_half.size(), "prediction.curve_half");
  if (!p.observation_half.empty()) need(p.observation_half.size(), "prediction.observation_half");
  if (opt.max_points == 0) throw std::invalid_argument("knoblab::fit::write_report: max_points must be positive");
}

}  // namespace

std::vector<plot::NamedFigure> report_figures(const FitResult& r, const FitData& data, const Prediction& p,
                                              const ReportOptions& opt) {
  check_inputs(data, p, opt);
  const AxisUnits& u = units(r.axis);
  const Inputs in{r,
                  data,
                  p,
                  opt,
                  data.size(),
                  !p.observation_half.empty(),
                  scaled(data.theta, u.position.scale),
                  scaled(data.omega, u.plot_speed.scale),
                  u};
  return {{"torque_position", position_figure(in)},
          {"torque_velocity", velocity_figure(in)},
          {"torque_time", time_figure(in)},
          {"ci_torque", ci_figure(in)}};
}

std::vector<fs::path> write_report(const FitResult& r, const FitData& data, const Prediction& p, const fs::path& dir,
                                   const ReportOptions& opt) {
  const auto figures = report_figures(r, data, p, opt);
  try {
    return plot::write_figures(figures, dir, opt.figure, [&opt](std::size_t done, std::size_t total) {
      opt.hooks.report("drawing the report", done, total);
      opt.hooks.check();
    });
  } catch (const Cancelled&) {
    throw;  // as it is: the command says "cancelled"
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("knoblab::fit::write_report: ") + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("knoblab::fit::write_report: ") + e.what());
  }
}

}  // namespace knoblab::fit
