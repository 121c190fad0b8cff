// Low-pass IIR design: analog prototype zeros/poles/gain → frequency scaling
// with prewarping → bilinear transform → pairing into biquads. Follows
// scipy.signal's buttap/cheb2ap/lp2lp_zpk/bilinear_zpk; the pairing is
// simpler than zpk2sos but gives the same overall transfer function.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "knoblab/model/filters.hpp"

namespace knoblab::model {
namespace {

using cd = std::complex<double>;
constexpr double kPi = std::numbers::pi;

struct Zpk {
  std::vector<cd> z, p;
  double k = 1.0;
};

void check_args(int order, double edge_hz, double fs_hz) {
  if (order < 1 || order > static_cast<int>(2 * SosCascade::kMaxSections))
    throw std::invalid_argument("filter order must be 1..20");
  if (!(fs_hz > 0.0) || !(edge_hz > 0.0) || !(edge_hz < fs_hz / 2.0))
    throw std::invalid_argument("filter edge must lie in (0, fs/2)");
}

// Butterworth prototype, cut-off 1 rad/s (scipy buttap).
Zpk butter_prototype(int n) {
  Zpk f;
  for (int m = -n + 1; m < n; m += 2)
    f.p.push_back(-std::exp(cd(0.0, kPi * m / (2.0 * n))));
  return f;
}

// Chebyshev II prototype, stop-band edge 1 rad/s (scipy cheb2ap).
Zpk cheby2_prototype(int n, double rs_db) {
  Zpk f;
  const double de = 1.0 / std::sqrt(std::pow(10.0, 0.1 * rs_db) - 1.0);
  const double mu = std::asinh(1.0 / de) / n;
  for (int m = -n + 1; m < n; m += 2) {
    if (m == 0) continue;  // odd order: that zero sits at infinity
    f.z.push_back(cd(0.0, 1.0 / std::sin(m * kPi / (2.0 * n))));
  }
  for (int m = -n + 1; m < n; m += 2) {
    const cd b = -std::exp(cd(0.0, kPi * m / (2.0 * n)));
    f.p.push_back(1.0 / cd(std::sinh(mu) * b.real(), std::cosh(mu) * b.imag()));
  }
  cd num = 1.0, den = 1.0;
  for (const cd& p : f.p) num *= -p;
  for (const cd& z : f.z) den *= -z;
  f.k = (num / den).real();
  return f;
}

// Scale the prototype to edge wo (rad/s), then map s → z with the bilinear
// transform at fs. Zeros at infinity land on z = −1.
Zpk to_digital(Zpk f, double wo, double fs) {
  for (cd& z : f.z) z *= wo;
  for (cd& p : f.p) p *= wo;
  f.k *= std::pow(wo, static_cast<double>(f.p.size() - f.z.size()));
  const double fs2 = 2.0 * fs;
  cd num = 1.0, den = 1.0;
  for (cd& z : f.z) {
    num *= fs2 - z;
    z = (fs2 + z) / (fs2 - z);
  }
  for (cd& p : f.p) {
    den *= fs2 - p;
    p = (fs2 + p) / (fs2 - p);
  }
  f.k *= (num / den).real();
  while (f.z.size() < f.p.size()) f.z.push_back(-1.0);
  return f;
}

bool is_real(const cd& v) { return std::abs(v.imag()) <= 1e-12 * std::max(1.0, std::abs(v)); }

// Take the root nearest to `target` from `pool` (real ones only if want_real).
cd take_nearest(std::vector<cd>& pool, const cd& target, bool want_real) {
  auto best = pool.end();
  for (auto it = pool.begin(); it != pool.end(); ++it) {
    if (is_real(*it) != want_real) continue;
    if (best == pool.end() || std::abs(*it - target) < std::abs(*best - target)) best = it;
  }
  if (best == pool.end()) throw std::logic_error("zpk pairing: no matching zero");
  const cd v = *best;
  pool.erase(best);
  return v;
}

// Up to two roots of one section; a lone complex root stands for the
// conjugate pair.
struct Roots {
  std::array<cd, 2> r{};
  std::size_t n = 0;
  void add(const cd& v) { r[n++] = v; }
};

// Coefficients c1, c2 of (1 − r0·z⁻¹)(1 − r1·z⁻¹).
void poly2(const Roots& roots, double& c1, double& c2) {
  const cd r0 = roots.r[0], r1 = roots.r[1];
  if (roots.n == 1 && !is_real(r0)) {
    c1 = -2.0 * r0.real();
    c2 = std::norm(r0);
  } else if (roots.n == 1) {
    c1 = -r0.real();
    c2 = 0.0;
  } else {
    c1 = -(r0.real() + r1.real());
    c2 = r0.real() * r1.real();
  }
}

// One biquad, monic in z⁻¹; the caller applies the gain.
Sos make_section(const Roots& zeros, const Roots& poles) {
  Sos s;
  s.b0 = 1.0;
  poly2(zeros, s.b1, s.b2);
  poly2(poles, s.a1, s.a2);
  return s;
}

// Pair poles with their nearest zeros, as zpk2sos(pairing='nearest') does:
// highest-Q poles (closest to the unit circle) pick zeros first and their
// sections go last. Each section gets unit DC gain; the leftover gain goes
// into the first section.
SosCascade to_sos(Zpk f) {
  std::vector<cd> complex_poles, real_poles;
  for (const cd& p : f.p) {
    if (is_real(p)) real_poles.push_back(p.real());
    else if (p.imag() > 0.0) complex_poles.push_back(p);
  }
  std::vector<cd> zeros;  // complex zeros: upper half only
  for (const cd& z : f.z)
    if (is_real(z) || z.imag() > 0.0) zeros.push_back(is_real(z) ? cd(z.real(), 0.0) : z);

  std::sort(complex_poles.begin(), complex_poles.end(),
            [](const cd& x, const cd& y) { return std::abs(x) > std::abs(y); });
  std::vector<Sos> reversed;  // built highest-Q first
  for (const cd& p : complex_poles) {
    const bool complex_zero_left =
        std::any_of(zeros.begin(), zeros.end(), [](const cd& z) { return !is_real(z); });
    Roots zs, ps;
    ps.add(p);
    if (complex_zero_left) {
      zs.add(take_nearest(zeros, p, false));
    } else {
      zs.add(take_nearest(zeros, p, true));
      zs.add(take_nearest(zeros, p, true));
    }
    reversed.push_back(make_section(zs, ps));
  }
  // Real poles (at most one for these designs, but pair any extras).
  std::sort(real_poles.begin(), real_poles.end(),
            [](const cd& x, const cd& y) { return std::abs(x) > std::abs(y); });
  for (std::size_t i = 0; i < real_poles.size(); i += 2) {
    Roots ps, zs;
    ps.add(real_poles[i]);
    if (i + 1 < real_poles.size()) ps.add(real_poles[i + 1]);
    for (std::size_t j = 0; j < ps.n; ++j) zs.add(take_nearest(zeros, ps.r[j], true));
    reversed.push_back(make_section(zs, ps));
  }
  std::vector<Sos> sections(reversed.rbegin(), reversed.rend());

  double applied = 1.0;
  for (Sos& s : sections) {
    const double num = s.b0 + s.b1 + s.b2;
    const double den = 1.0 + s.a1 + s.a2;
    const double g = (std::abs(num) > 1e-300) ? den / num : 1.0;
    s.b0 *= g;
    s.b1 *= g;
    s.b2 *= g;
    applied *= g;
  }
  const double rest = f.k / applied;
  sections.front().b0 *= rest;
  sections.front().b1 *= rest;
  sections.front().b2 *= rest;
  return SosCascade(sections);
}

}  // namespace

SosCascade design_butterworth_lowpass(int order, double cutoff_hz, double fs_hz) {
  check_args(order, cutoff_hz, fs_hz);
  const double warped = 2.0 * fs_hz * std::tan(kPi * cutoff_hz / fs_hz);
  return to_sos(to_digital(butter_prototype(order), warped, fs_hz));
}

SosCascade design_cheby2_lowpass(int order, double stop_atten_db, double stop_edge_hz,
                                 double fs_hz) {
  check_args(order, stop_edge_hz, fs_hz);
  if (!(stop_atten_db > 0.0)) throw std::invalid_argument("stop-band attenuation must be > 0 dB");
  const double warped = 2.0 * fs_hz * std::tan(kPi * stop_edge_hz / fs_hz);
  return to_sos(to_digital(cheby2_prototype(order, stop_atten_db), warped, fs_hz));
}

}  // namespace knoblab::model
