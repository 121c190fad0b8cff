// Karnopp stick band (Eq. 7) from data, instead of by eye (thesis §2.2.2.3).
//
// Inside the band the knob sticks: the friction torque is whatever the hand
// (here the motor) applies, up to D− / D+, not the sliding law's ±C + B·θ̇.
// So the sliding-law residual of raw τ_vel = τ − τ_acc − τ_pos is large near
// zero velocity. Binned by |θ̇| on a log scale, the band is the run of bins,
// from the slowest up, where most samples (more than half) are off the
// sliding law by more than three times the robust residual scale at speed;
// Δv is that run's upper edge. "Most", not an RMS excess: after breakaway a
// compliant gripper rings, and those few transients reach well past the
// stuck samples' speeds. D± are the extreme (99.5th percentile) raw τ_vel
// seen inside the band in each direction.
#include <algorithm>
#include <array>
#include <cmath>

#include "knoblab/model/quantile.hpp"
#include "residual.hpp"

namespace knoblab::fit::detail {

namespace {

constexpr std::size_t kBins = 30;
constexpr std::size_t kMinPerBin = 8;
constexpr double kExcess = 3.0;

}  // namespace

double strided_quantile(std::span<const double> v, double q) {
  const std::size_t stride = summary_stride(v.size());
  std::vector<double> sample;
  sample.reserve(v.size() / stride + 1);
  for (std::size_t i = 0; i < v.size(); i += stride) sample.push_back(v[i]);
  return model::quantile(std::move(sample), q);
}

std::optional<StickBand> estimate_stick_band(const FitData& d,
                                             std::span<const std::uint32_t> rows,
                                             std::span<const double> residual,
                                             const std::function<double(std::size_t)>& velocity_part) {
  const auto speed = [&](std::size_t j) { return std::abs(d.omega[rows[j]]); };
  double top = 0.0;
  for (std::size_t j = 0; j < rows.size(); ++j) top = std::max(top, speed(j));
  if (top <= 0) return std::nullopt;

  // Residual scale well away from zero velocity (median absolute deviation),
  // from the fast rows strided_quantile would take.
  const double fast = 0.2 * top;
  std::size_t n_fast = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) n_fast += speed(j) > fast ? 1 : 0;
  if (n_fast < 50) return std::nullopt;
  const std::size_t stride = summary_stride(n_fast);
  std::vector<double> outer;
  outer.reserve(n_fast / stride + 1);
  for (std::size_t j = 0, skip = 0; j < rows.size(); ++j) {
    if (!(speed(j) > fast)) continue;
    if (skip == 0) outer.push_back(residual[j]), skip = stride;
    --skip;
  }
  const double med = strided_quantile(outer, 0.5);
  for (double& x : outer) x = std::abs(x - med);
  const double sigma = 1.4826 * strided_quantile(outer, 0.5);

  // Log-spaced |θ̇| bins from 1e-4·top to the "fast" threshold: bin 0 below
  // edge[0] = lo, bin b in [edge[b−1], edge[b]), the last one open above.
  // Speeds change smoothly from row to row, so each row's bin is found by
  // walking from the previous one.
  const double lo = 1e-4 * top;
  const double ratio = std::pow(fast / lo, 1.0 / kBins);
  std::array<double, kBins> edge{};
  for (std::size_t b = 0; b < kBins; ++b) edge[b] = lo * std::pow(ratio, static_cast<double>(b));
  std::vector<std::size_t> off(kBins + 1, 0), count(kBins + 1, 0);
  std::size_t bin = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const double v = speed(j);
    if (v >= fast) continue;
    while (bin > 0 && v < edge[bin - 1]) --bin;
    while (bin < kBins && v >= edge[bin]) ++bin;
    off[bin] += std::abs(residual[j] - med) > kExcess * sigma ? 1 : 0;
    ++count[bin];
  }
  double dv = 0.0;
  bool started = false;
  for (std::size_t b = 0; b <= kBins; ++b) {
    if (count[b] < kMinPerBin) continue;
    if (2 * off[b] <= count[b]) break;
    started = true;
    dv = lo * std::pow(ratio, static_cast<double>(b));  // upper edge of bin b
  }
  if (!started) return std::nullopt;

  StickBand band;
  band.dv = dv;
  std::vector<double> inside;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    if (speed(j) < dv) inside.push_back(velocity_part(j) - residual[j]);  // raw τ_vel
  }
  band.samples = inside.size();
  if (inside.size() < kMinPerBin) return std::nullopt;
  band.D_pos = std::max(0.0, model::quantile(inside, 0.995));
  band.D_neg = std::max(0.0, -model::quantile(inside, 0.005));
  return band;
}

}  // namespace knoblab::fit::detail
