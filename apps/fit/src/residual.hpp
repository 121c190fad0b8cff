// The fit's residual: measured torque minus the model core's Eq. 6 torque,
// for a chunk of samples (one Ceres residual block per chunk keeps the
// per-block overhead small against 10⁵ samples). Internal to knoblab_fit.
#pragma once

#include <ceres/ceres.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "knoblab/fit/covariance.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/model/models.hpp"

namespace knoblab::fit::detail {

inline constexpr int kThesisParams = 8;
inline constexpr int kRenderParams = 5;  // M_acc, B_vel, A_pos, P_pos, S_pos
inline constexpr std::size_t kChunk = 512;

// Either parameter vector as the thesis model: render4 is Eq. 6 with no
// Coulomb friction and one damping coefficient.
template <typename T>
model::ThesisModel<T> as_thesis(ModelKind kind, const T* p) {
  if (kind == ModelKind::Thesis6) return model::ThesisModel<T>::from_params(p);
  model::ThesisModel<T> m;
  m.inertia.M = p[0];
  m.friction = {T(0), p[1], T(0), p[1]};
  m.detents.A = p[2];
  m.detents.P = p[3];
  m.detents.S = p[4];
  return m;
}

inline int param_count(ModelKind kind) {
  return kind == ModelKind::Thesis6 ? kThesisParams : kRenderParams;
}

struct ChunkResidual {
  ModelKind kind;
  const FitData* data;
  std::span<const std::uint32_t> rows;

  template <typename T>
  bool operator()(const T* p, T* residual) const {
    const model::ThesisModel<T> m = as_thesis(kind, p);
    for (std::size_t j = 0; j < rows.size(); ++j) {
      const std::uint32_t i = rows[j];
      const model::Kinematics<T> k{T(data->theta[i]), T(data->omega[i]), T(data->alpha[i])};
      residual[j] = m.torque(k) - T(data->torque[i]);
    }
    return true;
  }
};

template <int N>
std::unique_ptr<ceres::CostFunction> make_chunk_cost(ModelKind kind, const FitData& data,
                                                     std::span<const std::uint32_t> rows) {
  return std::make_unique<ceres::AutoDiffCostFunction<ChunkResidual, ceres::DYNAMIC, N>>(
      new ChunkResidual{kind, &data, rows}, static_cast<int>(rows.size()));
}

inline std::unique_ptr<ceres::CostFunction> make_chunk_cost(ModelKind kind, const FitData& data,
                                                            std::span<const std::uint32_t> rows) {
  return kind == ModelKind::Thesis6 ? make_chunk_cost<kThesisParams>(kind, data, rows)
                                    : make_chunk_cost<kRenderParams>(kind, data, rows);
}

// Residuals and the Jacobian (row-major, rows.size() × N) at p for the given
// rows, evaluated chunk by chunk with the same cost functions the fit uses.
void evaluate_rows(ModelKind kind, const FitData& data, std::span<const std::uint32_t> rows,
                   const double* p, std::span<double> residuals, std::span<double> jacobian);

// The detent search and linear starting values (start_values.cpp).
struct StartValues {
  std::vector<double> params;
  bool detents = false;
  double power = 0.0;        // explained share of the binned position residual
  double false_alarm = 1.0;  // chance of a peak this high from noise alone
  double period_lo = 0.0, period_hi = 0.0;  // P range searched (bounds for the fit)
};
StartValues find_start(const FitData& data, std::span<const std::uint32_t> rows,
                       const FitOptions& opt);

// Parameter covariance at the optimum (covariance.cpp; knoblab/fit/covariance.hpp).
using fit::CovarianceEstimate;
using fit::covariance_from_rows;
CovarianceEstimate estimate_covariance(ModelKind kind, const FitData& data,
                                       std::span<const std::uint32_t> rows, const double* p,
                                       const std::vector<bool>& fitted);

// Stick band from the sliding-law residual near zero velocity (stick_band.cpp).
// rows: the fitted rows of d; residual: theirs, model − measured (the sliding
// law's τ̂_vel − raw τ_vel); velocity_part(j): the model's τ̂_vel of rows[j],
// asked only of the rows inside the band (raw τ_vel = τ̂_vel − residual
// gives D±).
std::optional<StickBand> estimate_stick_band(const FitData& d,
                                             std::span<const std::uint32_t> rows,
                                             std::span<const double> residual,
                                             const std::function<double(std::size_t)>& velocity_part);

// The q-quantile of at most ~8 000 evenly strided values of v: robust scales
// and thresholds need no more (a median's standard error is then ~1.4 % of
// the scale), and selection over 10⁵ values costs more than the fit's passes.
double strided_quantile(std::span<const double> v, double q);
// The stride strided_quantile takes over n values (a caller that computes
// only every stride-th value gets the same quantile); summary figures over
// rows use it too.
inline std::size_t summary_stride(std::size_t n) { return n / 8000 > 1 ? n / 8000 : 1; }

}  // namespace knoblab::fit::detail
