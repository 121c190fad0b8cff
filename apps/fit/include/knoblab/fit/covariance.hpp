// Parameter covariance of a least-squares fit from its residuals and
// Jacobian: the sandwich estimate with batch means of the scores
// (covariance.cpp says why), which stays honest when the residuals of
// filtered, imperfectly modelled data are correlated. The thesis fit and the
// discovery's model fit (knoblab fit --model FILE) both take their
// intervals from it.
#pragma once

#include <cstddef>
#include <vector>

namespace knoblab::fit {

struct CovarianceEstimate {
  std::vector<double> covariance;  // N×N, zeros for held parameters
  std::vector<double> se;
  double t95 = 0.0;                // Student t for a 95 % interval: ci95 = t95·se
  double inflation = 1.0;          // the sandwich's variance over σ²(JᵀJ)⁻¹'s, mean
  double rss = 0.0;
  // Mean of the fitted torque's SD √(J·C·Jᵀ) over evenly strided rows (as
  // summary_stride takes them): a summary figure, not a per-row band.
  double curve_sd_mean = 0.0;
};

// From residuals (m rows, time order) and Jacobian rows (m × n, row-major) at
// the optimum; `fitted` marks the n parameters that were free.
CovarianceEstimate covariance_from_rows(std::vector<double> residuals, std::vector<double> jacobian,
                                        std::size_t n, const std::vector<bool>& fitted);

}  // namespace knoblab::fit
