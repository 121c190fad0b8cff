#include "absorption.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace knoblab::bench {

double unabsorbed_rms(const std::array<double, model::kThesisParamCount>& params, const fit::FitData& clean,
                      const fit::FitData& captured, const std::vector<std::size_t>& rows) {
  if (rows.empty()) return 0.0;
  for (const std::size_t i : rows)
    if (i >= captured.size() || i >= clean.size())
      throw std::invalid_argument("effect size: a row past the end of a capture");
  const auto n = static_cast<Eigen::Index>(rows.size());
  constexpr auto kParams = static_cast<Eigen::Index>(model::kThesisParamCount);
  const auto model = model::ThesisModel<double>::from_params(params.data());
  Eigen::VectorXd y(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    const std::size_t i = rows[static_cast<std::size_t>(r)];
    y(r) = (captured.torque[i] - model.torque(captured.kinematics(i))) -
           (clean.torque[i] - model.torque(clean.kinematics(i)));
  }
  Eigen::MatrixXd x(n, kParams);
  for (std::size_t k = 0; k < model::kThesisParamCount; ++k) {
    // Central differences: each term is smooth in its parameters off ω = 0,
    // and the rows are all moving.
    std::array<double, model::kThesisParamCount> up = params, down = params;
    const double h = 1e-6 * std::max(std::abs(params[k]), 1e-3);
    up[k] += h;
    down[k] -= h;
    const auto m_up = model::ThesisModel<double>::from_params(up.data());
    const auto m_down = model::ThesisModel<double>::from_params(down.data());
    for (Eigen::Index r = 0; r < n; ++r) {
      const auto kin = clean.kinematics(rows[static_cast<std::size_t>(r)]);
      x(r, static_cast<Eigen::Index>(k)) = (m_up.torque(kin) - m_down.torque(kin)) / (2.0 * h);
    }
  }
  // Rank-revealing: without detents, A's period and phase have no
  // sensitivity.
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(x);
  qr.setThreshold(1e-9);
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(n, qr.rank());
  const Eigen::VectorXd rest = y - q * (q.transpose() * y);
  return std::sqrt(rest.squaredNorm() / static_cast<double>(n));
}

}  // namespace knoblab::bench
