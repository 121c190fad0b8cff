// derivative(): second-order differences on irregular time stamps.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "knoblab/model/filters.hpp"
#include "reference.hpp"

namespace knoblab::model {
namespace {

// Irregular but deterministic stamps around 1 ms.
std::vector<double> irregular_times(std::size_t n, double h) {
  std::vector<double> t(n);
  double acc = 0.1;
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = acc;
    acc += h * (1.0 + 0.45 * std::sin(1.7 * static_cast<double>(i) + 0.3));
  }
  return t;
}

TEST(Derivative, ExactForQuadraticsOnIrregularTimes) {
  const std::vector<double> t = irregular_times(40, 1e-3);
  std::vector<double> x(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) x[i] = 3.0 - 2.0 * t[i] + 50.0 * t[i] * t[i];
  const std::vector<double> dx = derivative(t, x);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(dx[i], -2.0 + 100.0 * t[i], 1e-9) << i;
}

TEST(Derivative, SecondOrderAccurateForASineOnJitteredTimes) {
  // Three-point error is about x⁽³⁾·h²; the widest spacing here is 1.45·h.
  for (const double h : {2e-3, 1e-3, 5e-4}) {
    const std::vector<double> t = irregular_times(static_cast<std::size_t>(0.5 / h), h);
    std::vector<double> x(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) x[i] = std::sin(20.0 * t[i]);
    const std::vector<double> dx = derivative(t, x);
    for (std::size_t i = 0; i < t.size(); ++i)
      EXPECT_NEAR(dx[i], 20.0 * std::cos(20.0 * t[i]), 8000.0 * 1.45 * 1.45 * h * h) << i;
  }
}

TEST(Derivative, ErrorQuartersWhenTheStepHalves) {
  // Smoothly non-uniform stamps t = s + 0.1·sin(3s), s uniform, so halving
  // the step keeps the same shape of grid.
  double previous = 0.0;
  for (const double h : {4e-3, 2e-3, 1e-3}) {
    std::vector<double> t, x;
    for (double s = 0.0; s < 1.0; s += h) {
      t.push_back(s + 0.1 * std::sin(3.0 * s));
      x.push_back(std::sin(20.0 * t.back()));
    }
    const std::vector<double> dx = derivative(t, x);
    double worst = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i)
      worst = std::max(worst, std::abs(dx[i] - 20.0 * std::cos(20.0 * t[i])));
    if (previous > 0.0) {
      EXPECT_NEAR(previous / worst, 4.0, 0.5);
    }
    previous = worst;
  }
}

TEST(Derivative, MatchesNumpyGradientEdgeOrder2) {
  const test::Reference ref("model_gradient.txt");
  const std::vector<double> dx = derivative(ref["t"], ref["x"]);
  EXPECT_LT(test::relative_max_error(dx, ref["gradient"]), 1e-11);
}

TEST(Derivative, ShortInputs) {
  EXPECT_TRUE(derivative(std::vector<double>{}, std::vector<double>{}).empty());
  EXPECT_EQ(derivative(std::vector<double>{1.0}, std::vector<double>{5.0}),
            std::vector<double>{0.0});
  EXPECT_EQ(derivative(std::vector<double>{1.0, 1.5}, std::vector<double>{2.0, 3.0}),
            (std::vector<double>{2.0, 2.0}));
}

TEST(Derivative, RejectsBadTimeStamps) {
  EXPECT_THROW(derivative(std::vector<double>{0.0, 1.0, 1.0}, std::vector<double>{0, 1, 2}),
               std::invalid_argument);
  EXPECT_THROW(derivative(std::vector<double>{0.0, 1.0}, std::vector<double>{0, 1, 2}),
               std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::model
