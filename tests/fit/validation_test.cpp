// Thesis §2.1.2 done over many noise draws: data from Eq. 8–11, fitted with
// no starting values. Checks the 95% intervals' coverage and that the error
// matches plain least squares started at the truth (the statistical floor).
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/validation_data.hpp"

namespace knoblab::fit {
namespace {

// Eq. 6 written out by hand, independently of the model core.
struct PlainEq6 {
  double theta, omega, alpha, tau;
  template <typename T>
  bool operator()(const T* p, T* r) const {
    T vel = T(0);
    if (omega > 0) vel = p[3] + p[4] * omega;
    if (omega < 0) vel = -p[1] + p[2] * omega;
    r[0] = p[0] * alpha + vel + p[5] * sin(theta / p[6] + p[7]) - tau;
    return true;
  }
};

std::vector<double> plain_least_squares_from_truth(const FitData& d, std::vector<double> p) {
  ceres::Problem problem;
  for (std::size_t i = 0; i < d.size(); ++i) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PlainEq6, 1, 8>(
                                 new PlainEq6{d.theta[i], d.omega[i], d.alpha[i], d.torque[i]}),
                             nullptr, p.data());
  }
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.function_tolerance = 1e-12;
  o.parameter_tolerance = 1e-12;
  ceres::Solver::Summary s;
  ceres::Solve(o, &problem, &s);
  return p;
}

TEST(Validation, TwentySeedsCoverageAndErrorAtTheStatisticalFloor) {
  const ValidationSpec base;
  const std::vector<double>& truth = base.params;
  constexpr int kSeeds = 20;
  int covered = 0, pairs = 0;
  std::vector<double> sq_ours(8, 0.0), sq_plain(8, 0.0);
  for (int seed = 1; seed <= kSeeds; ++seed) {
    ValidationSpec spec;
    spec.seed = static_cast<std::uint64_t>(seed);
    const FitData d = make_validation_data(spec);
    const FitResult r = fit_knob(d);  // no starting values, no stick band in this data
    ASSERT_TRUE(r.detents) << "seed " << seed;
    const std::vector<double> plain = plain_least_squares_from_truth(d, truth);
    for (std::size_t k = 0; k < 8; ++k) {
      covered += (r.ci95[k][0] <= truth[k] && truth[k] <= r.ci95[k][1]) ? 1 : 0;
      ++pairs;
      sq_ours[k] += std::pow((r.params[k] - truth[k]) / truth[k], 2);
      sq_plain[k] += std::pow((plain[k] - truth[k]) / truth[k], 2);
    }
  }
  const double coverage = static_cast<double>(covered) / pairs;
  std::printf("95%% CI coverage over %d (seed, parameter) pairs: %.1f%%\n", pairs, 100 * coverage);
  std::printf("%-10s %12s %12s %8s\n", "param", "RMS err", "LS-truth", "ratio");
  for (std::size_t k = 0; k < 8; ++k) {
    const double ours = std::sqrt(sq_ours[k] / kSeeds), floor = std::sqrt(sq_plain[k] / kSeeds);
    std::printf("%-10s %11.4f%% %11.4f%% %8.3f\n", std::string(model::kThesisParamNames[k]).c_str(),
                100 * ours, 100 * floor, ours / floor);
    EXPECT_LE(ours, 1.10 * floor) << model::kThesisParamNames[k];
  }
  EXPECT_GE(coverage, 0.90);
}

}  // namespace
}  // namespace knoblab::fit
