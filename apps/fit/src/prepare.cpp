#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "knoblab/fit/fit_data.hpp"
#include "knoblab/model/filters.hpp"

namespace knoblab::fit {

namespace {

constexpr std::size_t kMinSamples = 100;

void check_capture(const interchange::Capture& c) {
  const std::size_t n = c.size();
  if (n < kMinSamples) {
    throw FitDataError("a fit needs at least " + std::to_string(kMinSamples) + " samples, got " +
                       std::to_string(n));
  }
  if (c.theta.size() != n || c.omega.size() != n || c.alpha.size() != n || c.torque.size() != n ||
      (!c.flags.empty() && c.flags.size() != n)) {
    throw FitDataError("the capture's channels have different lengths");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(c.t[i]) || !std::isfinite(c.theta[i]) || !std::isfinite(c.alpha[i]) ||
        !std::isfinite(c.torque[i])) {
      throw FitDataError("sample " + std::to_string(i) + " has a non-finite value");
    }
    if (i > 0 && !(c.t[i] > c.t[i - 1])) {
      throw FitDataError("sample times must increase (sample " + std::to_string(i) + ")");
    }
  }
  const auto [lo, hi] = std::minmax_element(c.theta.begin(), c.theta.end());
  if (*hi - *lo < 1e-3) throw FitDataError("the knob did not move (θ range < 1 mrad)");
}

// Median sample interval → rate: robust against one late sample.
double sample_rate(const std::vector<double>& t) {
  std::vector<double> dt(t.size() - 1);
  for (std::size_t i = 1; i < t.size(); ++i) dt[i - 1] = t[i] - t[i - 1];
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  return 1.0 / dt[dt.size() / 2];
}

// Time stamps from a host PC's clock (outside recordings) scatter around
// their median interval; the filters and differences assume one rate.
bool irregular(const std::vector<double>& t, double fs) {
  const double dt = 1.0 / fs;
  std::size_t off = 0;
  for (std::size_t i = 1; i < t.size(); ++i) off += std::abs(t[i] - t[i - 1] - dt) > 0.1 * dt ? 1 : 0;
  return off > t.size() / 100;
}

double interpolate(const std::vector<double>& x, std::size_t j, double w) {
  return x[j] + w * (x[j + 1] - x[j]);
}

// The capture linearly interpolated onto t0 + k/fs; a flag set on either
// neighbour stays set.
interchange::Capture resample(const interchange::Capture& c, double fs) {
  interchange::Capture r;
  r.alpha_derived = c.alpha_derived;
  r.omega_derived = c.omega_derived;
  const double t0 = c.t.front(), span = c.t.back() - t0;
  const auto n = static_cast<std::size_t>(std::floor(span * fs)) + 1;
  std::size_t j = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = std::min(t0 + static_cast<double>(k) / fs, c.t.back());
    while (j + 2 < c.size() && c.t[j + 1] < t) ++j;
    const double w = std::clamp((t - c.t[j]) / (c.t[j + 1] - c.t[j]), 0.0, 1.0);
    r.t.push_back(t);
    r.theta.push_back(interpolate(c.theta, j, w));
    r.omega.push_back(interpolate(c.omega, j, w));
    r.alpha.push_back(interpolate(c.alpha, j, w));
    r.torque.push_back(interpolate(c.torque, j, w));
    if (!c.flags.empty()) r.flags.push_back(c.flags[j] | c.flags[j + 1]);
  }
  return r;
}

// Whether Table 6's filter runs on a channel of n samples: not when the
// edge is too close to Nyquist for the filter to mean anything, nor on a
// channel shorter than its padding.
bool filters(const PrepOptions& o, double edge_hz, double fs, std::size_t n) {
  if (!o.filter || edge_hz >= 0.45 * fs) return false;
  return n > model::sosfiltfilt_padlen(model::design_cheby2_lowpass(o.order, o.stop_atten_db, edge_hz, fs));
}

// Table 6's filter on one channel, where it runs.
std::vector<double> lowpass(const PrepOptions& o, double edge_hz, double fs,
                            std::vector<double> x) {
  if (!filters(o, edge_hz, fs, x.size())) return x;
  return model::sosfiltfilt(model::design_cheby2_lowpass(o.order, o.stop_atten_db, edge_hz, fs), x);
}

}  // namespace

FitData prepare(const interchange::Capture& capture, const PrepOptions& opt) {
  const Axis axis = resolve_axis(capture, opt.axis);
  check_capture(capture);
  const double fs = sample_rate(capture.t);
  const bool resampled = irregular(capture.t, fs);
  std::optional<interchange::Capture> uniform;
  if (resampled) uniform = resample(capture, fs);
  const interchange::Capture& c = uniform ? *uniform : capture;
  const std::vector<double> theta = lowpass(opt, opt.edge_theta_hz, fs, c.theta);
  const std::vector<double> omega =
      lowpass(opt, opt.edge_omega_hz, fs, model::derivative(c.t, theta));
  const bool encoder = opt.alpha == AlphaSource::Encoder || c.alpha_derived;
  const std::vector<double> alpha =
      lowpass(opt, opt.edge_alpha_hz, fs, encoder ? model::derivative(c.t, omega) : c.alpha);
  const std::vector<double> torque = lowpass(opt, opt.edge_torque_hz, fs, c.torque);

  // Leave out the samples the loop flagged, after filtering the whole series.
  FitData d;
  d.rate_hz = fs;
  d.resampled = resampled;
  d.alpha_from_encoder = encoder;
  d.axis = axis;
  if (filters(opt, opt.edge_torque_hz, fs, c.size()))
    d.torque_lowpass = {opt.order, opt.stop_atten_db, opt.edge_torque_hz};
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!c.flags.empty() && (c.flags[i] & opt.exclude_flags)) continue;
    d.t.push_back(c.t[i]);
    d.theta.push_back(theta[i]);
    d.omega.push_back(omega[i]);
    d.alpha.push_back(alpha[i]);
    d.torque.push_back(torque[i]);
    d.torque_recorded.push_back(c.torque[i]);
  }
  if (d.size() < kMinSamples) {
    throw FitDataError("only " + std::to_string(d.size()) +
                       " samples are left after excluding flagged ones (e-stop, fault, "
                       "torque limit)");
  }
  return d;
}

}  // namespace knoblab::fit
