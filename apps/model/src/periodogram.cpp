// Angular periodogram by accumulated normal equations. Per frequency we need
// Σs, Σc, Σs², Σc², Σsc, Σỹs, Σỹc (ỹ = y − ȳ); sin/cos of f·θ for successive
// f come from rotating the previous pair by df·θ (angle addition), with an
// exact re-seed every kReseed frequencies to stop rounding drift.
#include "knoblab/model/periodogram.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace knoblab::model {
namespace {

constexpr std::size_t kReseed = 64;

struct Sums {
  double s = 0, c = 0, ss = 0, cc = 0, sc = 0, ys = 0, yc = 0;
};

struct Prepared {
  std::vector<double> yc;  // y − ȳ
  double mean = 0.0;
  double tss = 0.0;  // Σ(y − ȳ)²
};

Prepared prepare(std::span<const double> theta, std::span<const double> y) {
  if (theta.size() != y.size()) throw std::invalid_argument("periodogram: theta and y differ in size");
  if (y.size() < 3) throw std::invalid_argument("periodogram: needs at least 3 samples");
  Prepared p;
  for (double v : y) p.mean += v;
  p.mean /= static_cast<double>(y.size());
  p.yc.resize(y.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    p.yc[i] = y[i] - p.mean;
    p.tss += p.yc[i] * p.yc[i];
  }
  return p;
}

// Least squares y ≈ a·s + b·c + offset from the sums: regress ỹ on the
// centred regressors (2×2 normal equations).
SinusoidFit solve(const Sums& m, const Prepared& p, double n, double f) {
  SinusoidFit fit;
  fit.frequency = f;
  fit.offset = p.mean;
  const double gss = m.ss - m.s * m.s / n;
  const double gcc = m.cc - m.c * m.c / n;
  const double gsc = m.sc - m.s * m.c / n;
  const double trace = gss + gcc;
  if (!(p.tss > 0.0) || !(trace > 1e-12 * n)) return fit;
  double a = 0.0, b = 0.0;
  const double det = gss * gcc - gsc * gsc;
  if (det > 1e-10 * trace * trace) {
    a = (gcc * m.ys - gsc * m.yc) / det;
    b = (gss * m.yc - gsc * m.ys) / det;
  } else if (gss >= gcc) {  // regressors (nearly) collinear: fit the stronger one
    a = m.ys / gss;
  } else {
    b = m.yc / gcc;
  }
  fit.power = std::clamp((a * m.ys + b * m.yc) / p.tss, 0.0, 1.0);
  fit.amplitude = std::hypot(a, b);
  fit.phase = std::atan2(b, a);  // A·sin(x + S) = A·cos S·sin x + A·sin S·cos x
  fit.offset = p.mean - (a * m.s + b * m.c) / n;
  return fit;
}

SinusoidFit fit_prepared(std::span<const double> theta, const Prepared& p, double f) {
  Sums m;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const double s = std::sin(f * theta[i]), c = std::cos(f * theta[i]);
    m.s += s;
    m.c += c;
    m.ss += s * s;
    m.cc += c * c;
    m.sc += s * c;
    m.ys += p.yc[i] * s;
    m.yc += p.yc[i] * c;
  }
  return solve(m, p, static_cast<double>(theta.size()), f);
}

}  // namespace

SinusoidFit fit_sinusoid(std::span<const double> theta, std::span<const double> y, double f) {
  return fit_prepared(theta, prepare(theta, y), f);
}

AngularPeriodogram angular_periodogram(std::span<const double> theta, std::span<const double> y,
                                       double f_min, double f_max, double df) {
  const Prepared p = prepare(theta, y);
  if (!(df > 0.0) || !(f_min >= 0.0) || !(f_max >= f_min))
    throw std::invalid_argument("periodogram: need df > 0 and 0 <= f_min <= f_max");
  const auto nf = static_cast<std::size_t>(std::floor((f_max - f_min) / df + 1e-9)) + 1;
  const std::size_t n = theta.size();
  const double nd = static_cast<double>(n);

  AngularPeriodogram out;
  out.frequency.resize(nf);
  out.power.resize(nf);
  std::vector<double> s(n), c(n), rot_c(n), rot_s(n);
  for (std::size_t i = 0; i < n; ++i) {
    rot_c[i] = std::cos(df * theta[i]);
    rot_s[i] = std::sin(df * theta[i]);
  }
  for (std::size_t k = 0; k < nf; ++k) {
    const double f = f_min + static_cast<double>(k) * df;
    if (k % kReseed == 0) {
      for (std::size_t i = 0; i < n; ++i) {
        s[i] = std::sin(f * theta[i]);
        c[i] = std::cos(f * theta[i]);
      }
    }
    Sums m;
    for (std::size_t i = 0; i < n; ++i) {
      const double si = s[i], ci = c[i];
      m.s += si;
      m.c += ci;
      m.ss += si * si;
      m.cc += ci * ci;
      m.sc += si * ci;
      m.ys += p.yc[i] * si;
      m.yc += p.yc[i] * ci;
      s[i] = si * rot_c[i] + ci * rot_s[i];  // advance to f + df
      c[i] = ci * rot_c[i] - si * rot_s[i];
    }
    out.frequency[k] = f;
    out.power[k] = solve(m, p, nd, f).power;
  }

  const auto best = static_cast<std::size_t>(
      std::max_element(out.power.begin(), out.power.end()) - out.power.begin());
  double f_peak = out.frequency[best];
  if (best > 0 && best + 1 < nf) {
    const double pm = out.power[best - 1], p0 = out.power[best], pp = out.power[best + 1];
    const double curvature = pm - 2.0 * p0 + pp;
    if (curvature < 0.0) f_peak += std::clamp(0.5 * (pm - pp) / curvature, -0.5, 0.5) * df;
  }
  out.peak = fit_prepared(theta, p, f_peak);
  if (out.peak.power < out.power[best]) out.peak = fit_prepared(theta, p, out.frequency[best]);
  return out;
}

}  // namespace knoblab::model
