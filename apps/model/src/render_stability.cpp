#include "knoblab/model/render_stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace knoblab::model {
namespace {

using Matrix = std::vector<double>;  // row-major, square

Matrix multiply(const Matrix& a, const Matrix& b, int n) {
  Matrix c(static_cast<std::size_t>(n * n), 0.0);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const double aik = a[i * n + k];
      if (aik == 0.0) continue;
      for (int j = 0; j < n; ++j) c[i * n + j] += aik * b[k * n + j];
    }
  return c;
}

// e^M by scaling and squaring with a Taylor series: M is small (≤ 6 × 6)
// and its scaled norm ≤ 1/4, where 20 terms are exact to rounding.
Matrix expm(Matrix m, int n) {
  double norm = 0.0;
  for (int j = 0; j < n; ++j) {
    double col = 0.0;
    for (int i = 0; i < n; ++i) col += std::abs(m[i * n + j]);
    norm = std::max(norm, col);
  }
  const int s = norm > 0.25 ? static_cast<int>(std::ceil(std::log2(norm / 0.25))) : 0;
  const double scale = std::ldexp(1.0, -s);
  for (double& v : m) v *= scale;
  Matrix result(static_cast<std::size_t>(n * n), 0.0), term(result);
  for (int i = 0; i < n; ++i) result[i * n + i] = term[i * n + i] = 1.0;
  for (int k = 1; k <= 20; ++k) {
    term = multiply(term, m, n);
    for (double& v : term) v /= k;
    for (std::size_t i = 0; i < result.size(); ++i) result[i] += term[i];
  }
  for (int i = 0; i < s; ++i) result = multiply(result, result, n);
  return result;
}

// Parlett–Reinsch balancing by powers of 2 (a similarity, so exact): the
// loop's states span rad, rad/s and N·m, and unbalanced rows cost QR digits.
void balance(Matrix& a, int n) {
  constexpr double kRadix = 2.0;
  bool done = false;
  while (!done) {
    done = true;
    for (int i = 0; i < n; ++i) {
      double c = 0.0, r = 0.0;
      for (int j = 0; j < n; ++j)
        if (j != i) {
          c += std::abs(a[j * n + i]);
          r += std::abs(a[i * n + j]);
        }
      if (c == 0.0 || r == 0.0) continue;
      double g = r / kRadix, f = 1.0;
      const double sum = c + r;
      while (c < g) {
        f *= kRadix;
        c *= kRadix * kRadix;
      }
      g = r * kRadix;
      while (c > g) {
        f /= kRadix;
        c /= kRadix * kRadix;
      }
      if ((c + r) / f < 0.95 * sum) {
        done = false;
        for (int j = 0; j < n; ++j) a[i * n + j] /= f;
        for (int j = 0; j < n; ++j) a[j * n + i] *= f;
      }
    }
  }
}

}  // namespace

std::vector<std::complex<double>> eigenvalues(std::vector<double> a, int n) {
  using C = std::complex<double>;
  if (n <= 0) return {};
  balance(a, n);
  // Householder reduction to upper Hessenberg form.
  for (int k = 0; k + 2 < n; ++k) {
    double alpha = 0.0;
    for (int i = k + 1; i < n; ++i) alpha += a[i * n + k] * a[i * n + k];
    alpha = std::sqrt(alpha);
    if (alpha == 0.0) continue;
    if (a[(k + 1) * n + k] > 0.0) alpha = -alpha;
    std::vector<double> v(static_cast<std::size_t>(n), 0.0);
    v[k + 1] = a[(k + 1) * n + k] - alpha;
    for (int i = k + 2; i < n; ++i) v[i] = a[i * n + k];
    double vv = 0.0;
    for (int i = k + 1; i < n; ++i) vv += v[i] * v[i];
    if (vv == 0.0) continue;
    for (int j = 0; j < n; ++j) {  // A ← (I − 2vvᵀ/vᵀv) A
      double d = 0.0;
      for (int i = k + 1; i < n; ++i) d += v[i] * a[i * n + j];
      d *= 2.0 / vv;
      for (int i = k + 1; i < n; ++i) a[i * n + j] -= d * v[i];
    }
    for (int i = 0; i < n; ++i) {  // A ← A (I − 2vvᵀ/vᵀv)
      double d = 0.0;
      for (int j = k + 1; j < n; ++j) d += a[i * n + j] * v[j];
      d *= 2.0 / vv;
      for (int j = k + 1; j < n; ++j) a[i * n + j] -= d * v[j];
    }
  }
  std::vector<C> h(a.begin(), a.end());
  const auto H = [&](int i, int j) -> C& { return h[static_cast<std::size_t>(i * n + j)]; };
  std::vector<C> eig(static_cast<std::size_t>(n));
  std::vector<C> cs(static_cast<std::size_t>(n)), sn(static_cast<std::size_t>(n));
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  int hi = n - 1, iter = 0;
  while (hi >= 0) {
    int l = hi;
    while (l > 0 && std::abs(H(l, l - 1)) > kEps * (std::abs(H(l - 1, l - 1)) + std::abs(H(l, l)))) --l;
    if (l > 0) H(l, l - 1) = 0.0;
    if (l == hi) {  // a 1 × 1 block has deflated
      eig[static_cast<std::size_t>(hi)] = H(hi, hi);
      --hi;
      iter = 0;
      continue;
    }
    if (++iter > 300) throw std::runtime_error("eigenvalues: QR did not converge");
    // Wilkinson shift: the eigenvalue of the trailing 2 × 2 nearer its
    // corner; now and then an exceptional one to break a cycle.
    C mu;
    if (iter % 11 == 10) {
      mu = H(hi, hi) + std::abs(H(hi, hi - 1)) * 0.75;
    } else {
      const C p = H(hi - 1, hi - 1), q = H(hi - 1, hi), r = H(hi, hi - 1), s = H(hi, hi);
      const C half = 0.5 * (p + s);
      const C disc = std::sqrt(half * half - (p * s - q * r));
      const C m1 = half + disc, m2 = half - disc;
      mu = std::abs(m1 - s) < std::abs(m2 - s) ? m1 : m2;
    }
    // One QR step on the active block [l, hi]: H − μI = QR, H ← RQ + μI.
    for (int k = l; k <= hi; ++k) H(k, k) -= mu;
    for (int k = l; k < hi; ++k) {
      const C x = H(k, k), y = H(k + 1, k);
      const double r = std::hypot(std::abs(x), std::abs(y));
      const C c = r > 0.0 ? x / r : C(1.0), s = r > 0.0 ? y / r : C(0.0);
      cs[static_cast<std::size_t>(k)] = c;
      sn[static_cast<std::size_t>(k)] = s;
      for (int j = k; j <= hi; ++j) {
        const C u = H(k, j), w = H(k + 1, j);
        H(k, j) = std::conj(c) * u + std::conj(s) * w;
        H(k + 1, j) = -s * u + c * w;
      }
    }
    for (int k = l; k < hi; ++k) {
      const C c = cs[static_cast<std::size_t>(k)], s = sn[static_cast<std::size_t>(k)];
      for (int i = l; i <= std::min(k + 1, hi); ++i) {
        const C u = H(i, k), w = H(i, k + 1);
        H(i, k) = u * c + w * s;
        H(i, k + 1) = -u * std::conj(s) + w * std::conj(c);
      }
    }
    for (int k = l; k <= hi; ++k) H(k, k) += mu;
  }
  return eig;
}

LoopStability::LoopStability(const LoopDynamics& d) : d_(d) {
  const bool two_body = d.rotor_inertia > 0.0 && d.coupling_stiffness > 0.0;
  const bool lag = d.actuator_bandwidth_hz > 0.0;
  if (!(d.rate_hz > 0.0) || !(d.inertia > 0.0) || !(d.damping >= 0.0) || !(d.grip_stiffness >= 0.0) ||
      !(d.coupling_damping >= 0.0) || !(d.actuator_bandwidth_hz >= 0.0))
    throw std::invalid_argument("LoopDynamics: rate and inertia must be positive, damping and stiffness not negative");
  const double T = 1.0 / d.rate_hz;
  filter_.assign(0, Sos{});
  const SosCascade f = design_butterworth_lowpass(d.velocity_filter_order, d.velocity_cutoff_hz, d.rate_hz);
  filter_.assign(f.sections().begin(), f.sections().end());

  // Continuous plant ẋ = A x + b u; u the motor torque (N·m, +θ).
  np_ = (two_body ? 4 : 2) + (lag ? 1 : 0);
  const int m = np_ + 1;  // augmented with the held input
  Matrix A(static_cast<std::size_t>(m * m), 0.0);
  const auto at = [&](int i, int j) -> double& { return A[static_cast<std::size_t>(i * m + j)]; };
  const int u_at = lag ? np_ - 1 : np_;  // where the torque acting on the rotor lives
  if (two_body) {
    // [θ_m, ω_m, θ_k, ω_k]: the encoder and motor on the rotor, the grip on the knob.
    const double Jm = d.rotor_inertia, Jk = d.inertia, kc = d.coupling_stiffness, cc = d.coupling_damping;
    at(0, 1) = 1.0;
    at(1, 0) = -kc / Jm, at(1, 1) = -cc / Jm, at(1, 2) = kc / Jm, at(1, 3) = cc / Jm;
    at(1, u_at) += 1.0 / Jm;
    at(2, 3) = 1.0;
    at(3, 0) = kc / Jk, at(3, 1) = cc / Jk, at(3, 2) = -(kc + d.grip_stiffness) / Jk;
    at(3, 3) = -(cc + d.damping) / Jk;
  } else {
    at(0, 1) = 1.0;
    at(1, 0) = -d.grip_stiffness / d.inertia, at(1, 1) = -d.damping / d.inertia;
    at(1, u_at) += 1.0 / d.inertia;
  }
  if (lag) {  // τ̇ = ω_a (u − τ)
    const double wa = 2.0 * std::numbers::pi * d.actuator_bandwidth_hz;
    at(np_ - 1, np_ - 1) = -wa;
    at(np_ - 1, np_) = wa;
  }
  out_ = 0;
  for (double& v : A) v *= T;
  const Matrix E = expm(std::move(A), m);
  phi_.resize(static_cast<std::size_t>(np_ * np_));
  gamma_.resize(static_cast<std::size_t>(np_));
  for (int i = 0; i < np_; ++i) {
    for (int j = 0; j < np_; ++j) phi_[static_cast<std::size_t>(i * np_ + j)] = E[static_cast<std::size_t>(i * m + j)];
    gamma_[static_cast<std::size_t>(i)] = E[static_cast<std::size_t>(i * m + np_)];
  }
}

// One loop cycle on the stacked state z = [plant, θ_k−1, filter states]:
//   y = θ_k; v = (y − θ_k−1)/T through the Butterworth (transposed direct
//   form II, as SosCascade) → ω̂; u = −(K·y + B·ω̂) held for T.
void LoopStability::step(const double* z, double K, double B, double* next) const {
  const double* x = z;
  const double y = x[out_];
  const double prev = z[np_];
  const double* s = z + np_ + 1;
  double* s_next = next + np_ + 1;
  double in = (y - prev) * d_.rate_hz;
  for (std::size_t i = 0; i < filter_.size(); ++i) {
    const Sos& f = filter_[i];
    const double o = f.b0 * in + s[2 * i];
    s_next[2 * i] = f.b1 * in - f.a1 * o + s[2 * i + 1];
    s_next[2 * i + 1] = f.b2 * in - f.a2 * o;
    in = o;
  }
  const double u = -(K * y + B * in);
  for (int i = 0; i < np_; ++i) {
    double v = gamma_[static_cast<std::size_t>(i)] * u;
    for (int j = 0; j < np_; ++j) v += phi_[static_cast<std::size_t>(i * np_ + j)] * x[j];
    next[i] = v;
  }
  next[np_] = y;
}

std::vector<double> LoopStability::closed_loop(double K, double B, int& n) const {
  n = np_ + 1 + 2 * static_cast<int>(filter_.size());
  std::vector<double> a(static_cast<std::size_t>(n * n), 0.0), e(static_cast<std::size_t>(n)),
      col(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {  // the map is linear: its columns are the images of the basis
    std::fill(e.begin(), e.end(), 0.0);
    e[static_cast<std::size_t>(j)] = 1.0;
    step(e.data(), K, B, col.data());
    for (int i = 0; i < n; ++i) a[static_cast<std::size_t>(i * n + j)] = col[static_cast<std::size_t>(i)];
  }
  return a;
}

double LoopStability::spectral_radius(double K, double B) const {
  int n = 0;
  std::vector<double> a = closed_loop(K, B, n);  // sets n: not in the same call's arguments
  const std::vector<std::complex<double>> eig = eigenvalues(std::move(a), n);
  // On a falling side steeper than the grip, the largest real root above 1
  // is the knob falling away as drawn: set aside once.
  bool fall_allowed = K + d_.grip_stiffness < 0.0;
  std::size_t fall = eig.size();
  if (fall_allowed) {
    double largest = 1.0;
    for (std::size_t i = 0; i < eig.size(); ++i)
      if (std::abs(eig[i].imag()) <= 1e-9 * std::abs(eig[i]) && eig[i].real() > largest) {
        largest = eig[i].real();
        fall = i;
      }
  }
  double rho = 0.0;
  for (std::size_t i = 0; i < eig.size(); ++i)
    if (i != fall) rho = std::max(rho, std::abs(eig[i]));
  return rho;
}

bool LoopStability::renders_stably(double K, double B) const {
  if (!std::isfinite(K) || !std::isfinite(B)) return false;
  // A root on the circle itself is a knob left where it is (no grip
  // stiffness: the free rigid body's z = 1), not a ring that grows.
  return spectral_radius(K, B) <= 1.0 + 1e-9;
}

namespace {

// The edge of the stable set along one direction from a stable start:
// expand until unstable, then bisect to 1e-4 relative.
template <typename Stable>
double edge(Stable stable, double direction) {
  if (!stable(0.0)) return std::numeric_limits<double>::quiet_NaN();
  double good = 0.0, bad = 1e-3;
  while (stable(direction * bad)) {
    good = bad;
    bad *= 4.0;
    if (bad > 1e9) return direction * std::numeric_limits<double>::infinity();
  }
  while (bad - good > 1e-4 * bad) {
    const double mid = 0.5 * (good + bad);
    (stable(direction * mid) ? good : bad) = mid;
  }
  return direction * good;
}

}  // namespace

double LoopStability::max_stiffness(double B) const {
  return edge([&](double K) { return renders_stably(K, B); }, 1.0);
}
double LoopStability::max_damping(double K) const {
  return edge([&](double B) { return renders_stably(K, B); }, 1.0);
}
double LoopStability::min_damping(double K) const {
  return edge([&](double B) { return renders_stably(K, B); }, -1.0);
}
double LoopStability::min_stiffness(double B) const {
  return edge([&](double K) { return renders_stably(K, B); }, -1.0);
}

bool renders_stably(const LoopDynamics& d, double K, double B) { return LoopStability(d).renders_stably(K, B); }
double max_stiffness(const LoopDynamics& d, double B) { return LoopStability(d).max_stiffness(B); }
double max_damping(const LoopDynamics& d, double K) { return LoopStability(d).max_damping(K); }
double min_damping(const LoopDynamics& d, double K) { return LoopStability(d).min_damping(K); }

}  // namespace knoblab::model
