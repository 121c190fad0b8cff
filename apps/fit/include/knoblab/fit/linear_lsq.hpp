// Linear least squares y ≈ Σ β_k·x_k as an accumulator of the normal
// equations (XᵀX, Xᵀy, yᵀy, n): trivially copyable and allocation-free, so a
// realtime loop can feed it sample by sample; solve() (which may throw) is for
// non-realtime code. N is small here (≤ 4), so the normal equations are well
// enough conditioned in double.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace knoblab::fit {

template <std::size_t N>
class LinearLsq {
 public:
  void add(const std::array<double, N>& x, double y) noexcept {
    for (std::size_t i = 0; i < N; ++i) {
      for (std::size_t j = 0; j < N; ++j) xtx_[i][j] += x[i] * x[j];
      xty_[i] += x[i] * y;
    }
    yty_ += y * y;
    ++n_;
  }
  std::int64_t count() const noexcept { return n_; }

  struct Solution {
    std::array<double, N> beta{};
    std::array<std::array<double, N>, N> cov{};  // σ̂²·(XᵀX)⁻¹
    std::array<double, N> se{};                  // standard errors, √diag(cov)
    std::array<double, N> ci95{};                // 95% half-widths, t(0.975, dof)·se
    double residual_sd = 0.0;                    // σ̂ = √(RSS / dof)
    std::int64_t n = 0;
    std::int64_t dof = 0;                        // n − N, of σ̂ and so of every interval
  };
  // Throws FitDataError (fit_data.hpp) for n ≤ N + 1 samples or a singular
  // design.
  Solution solve() const;

 private:
  std::array<std::array<double, N>, N> xtx_{};
  std::array<double, N> xty_{};
  double yty_ = 0.0;
  std::int64_t n_ = 0;
};

extern template class LinearLsq<1>;
extern template class LinearLsq<2>;
extern template class LinearLsq<3>;
extern template class LinearLsq<4>;

}  // namespace knoblab::fit
