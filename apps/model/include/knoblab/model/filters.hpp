// Signal conditioning for captured and rendered signals.
//
// IIR low-pass filters as cascades of second-order sections (SOS), designed
// the way scipy.signal.butter / cheby2 (output='sos') design them, so offline
// results can be checked against scipy. The streaming path (SosCascade::process,
// BoxFilter3::process) runs in the 10 kHz render loop: no allocation, no
// locks, no exceptions. Units: Hz for frequencies, anything for samples.
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <span>
#include <vector>

namespace knoblab::model {

// One biquad, a0 normalised to 1:
//   H(z) = (b0 + b1 z⁻¹ + b2 z⁻²) / (1 + a1 z⁻¹ + a2 z⁻²).
// A first-order section has b2 = a2 = 0.
struct Sos {
  double b0{1}, b1{}, b2{}, a1{}, a2{};
};

// Up to kMaxSections biquads in series (order ≤ 20), each in transposed
// direct form II. Storage is inline so copies and processing never allocate.
class SosCascade {
 public:
  static constexpr std::size_t kMaxSections = 10;

  SosCascade() = default;
  // Throws std::invalid_argument for more than kMaxSections sections.
  explicit SosCascade(std::span<const Sos> sections);

  // One sample through the cascade (causal, streaming).
  double process(double x) noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      const Sos& s = sections_[i];
      State& z = state_[i];
      const double y = s.b0 * x + z[0];
      z[0] = s.b1 * x - s.a1 * y + z[1];
      z[1] = s.b2 * x - s.a2 * y;
      x = y;
    }
    return x;
  }

  // All delay states to zero.
  void reset() noexcept;
  // States as if the input had been x forever (scipy's sosfilt_zi · x), so
  // starting on a non-zero signal does not produce a start-up transient.
  void reset_to_steady_state(double x) noexcept;

  std::size_t size() const noexcept { return count_; }
  std::span<const Sos> sections() const noexcept { return {sections_.data(), count_}; }
  // H(e^{j2πf/fs}).
  std::complex<double> response(double f_hz, double fs_hz) const noexcept;
  // H(1): output / input for a constant input.
  double dc_gain() const noexcept;

 private:
  using State = std::array<double, 2>;
  std::array<Sos, kMaxSections> sections_{};
  std::array<State, kMaxSections> state_{};
  std::size_t count_ = 0;
};

// scipy.signal.butter(order, cutoff_hz, fs=fs_hz, output='sos').
// order 1..20, 0 < cutoff_hz < fs_hz/2; throws std::invalid_argument otherwise.
SosCascade design_butterworth_lowpass(int order, double cutoff_hz, double fs_hz);

// scipy.signal.cheby2(order, stop_atten_db, stop_edge_hz, fs=fs_hz, output='sos'):
// the response is down by stop_atten_db at stop_edge_hz and beyond.
// order 1..20, stop_atten_db > 0, 0 < stop_edge_hz < fs_hz/2.
SosCascade design_cheby2_lowpass(int order, double stop_atten_db, double stop_edge_hz,
                                 double fs_hz);

// Offline, causal, from zero state (scipy.signal.sosfilt). `filter`'s own
// state is not used or changed.
std::vector<double> sosfilt(const SosCascade& filter, std::span<const double> x);

// Offline zero-phase forward–backward filtering with scipy.signal.sosfiltfilt's
// defaults: odd extension of 3·ntaps samples at each end and steady-state
// initial conditions. Throws std::invalid_argument if x is not longer than the
// padding (scipy raises ValueError there).
std::vector<double> sosfiltfilt(const SosCascade& filter, std::span<const double> x);
// The padding sosfiltfilt uses for this filter.
std::size_t sosfiltfilt_padlen(const SosCascade& filter) noexcept;

// Mean of the last three samples: the thesis' "Low Pass 2" on τ_acc (§3.2).
class BoxFilter3 {
 public:
  double process(double x) noexcept {
    h_[2] = h_[1];
    h_[1] = h_[0];
    h_[0] = x;
    return (h_[0] + h_[1] + h_[2]) / 3.0;
  }
  // History to zero: the first two outputs ramp up from 0.
  void reset() noexcept { h_ = {}; }
  // History to x: a constant x passes straight through.
  void reset_to_steady_state(double x) noexcept { h_ = {x, x, x}; }

 private:
  std::array<double, 3> h_{};
};

// dx/dt on possibly irregular time stamps: second-order accurate three-point
// differences (central inside, one-sided at both ends), the same as
// numpy.gradient(x, t, edge_order=2). Exact for quadratics. Two samples give
// the plain difference quotient; fewer give zeros.
// Throws std::invalid_argument if the sizes differ or t is not strictly
// increasing.
std::vector<double> derivative(std::span<const double> t, std::span<const double> x);

}  // namespace knoblab::model
