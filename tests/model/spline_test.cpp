// CubicSpline against scipy.interpolate.CubicSpline and its own properties.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "knoblab/model/spline.hpp"
#include "reference.hpp"

namespace knoblab::model {
namespace {

const test::Reference& ref() {
  static const test::Reference r("model_splines.txt");
  return r;
}

std::vector<double> eval(const CubicSpline& s, const std::vector<double>& x) {
  std::vector<double> y;
  for (double v : x) y.push_back(s(v));
  return y;
}

TEST(CubicSpline, NaturalMatchesScipy) {
  const CubicSpline s(ref()["natural.x"], ref()["natural.y"], SplineBoundary::kNatural);
  const std::vector<double>& xe = ref()["natural.xe"];  // includes extrapolation
  EXPECT_LT(test::relative_max_error(eval(s, xe), ref()["natural.value"]), 1e-12);
  std::vector<double> d1;
  for (double v : xe) d1.push_back(s.derivative(v));
  EXPECT_LT(test::relative_max_error(d1, ref()["natural.d1"]), 1e-12);
}

TEST(CubicSpline, PeriodicMatchesScipy) {
  const CubicSpline s(ref()["periodic.x"], ref()["periodic.y"], SplineBoundary::kPeriodic);
  const std::vector<double>& xe = ref()["periodic.xe"];  // wraps outside the knots
  EXPECT_LT(test::relative_max_error(eval(s, xe), ref()["periodic.value"]), 1e-12);
  std::vector<double> d1;
  for (double v : xe) d1.push_back(s.derivative(v));
  EXPECT_LT(test::relative_max_error(d1, ref()["periodic.d1"]), 1e-12);
}

TEST(CubicSpline, PeriodicWithThreeKnotsMatchesScipy) {
  const CubicSpline s(ref()["periodic3.x"], ref()["periodic3.y"], SplineBoundary::kPeriodic);
  EXPECT_LT(test::relative_max_error(eval(s, ref()["periodic3.xe"]), ref()["periodic3.value"]),
            1e-12);
}

TEST(CubicSpline, InterpolatesItsKnots) {
  const std::vector<double> x{-1.0, 0.2, 0.25, 2.0, 7.0}, y{3.0, -1.0, 0.5, 0.5, 2.0};
  const CubicSpline s(x, y);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(s(x[i]), y[i], 1e-13);
}

TEST(CubicSpline, NaturalEndsHaveNoCurvature) {
  const CubicSpline s(ref()["natural.x"], ref()["natural.y"]);
  const double h = 1e-5;
  for (const double end : {s.x_min(), s.x_max()}) {
    const double curvature = (s.derivative(end + h) - s.derivative(end - h)) / (2 * h);
    EXPECT_NEAR(curvature, 0.0, 1e-8);
  }
}

TEST(CubicSpline, TwoKnotsGiveALine) {
  const CubicSpline s(std::vector<double>{1.0, 3.0}, std::vector<double>{2.0, 6.0});
  EXPECT_DOUBLE_EQ(s(2.0), 4.0);
  EXPECT_DOUBLE_EQ(s(5.0), 10.0);
  EXPECT_DOUBLE_EQ(s.derivative(0.0), 2.0);
}

TEST(CubicSpline, PeriodicRepeatsWithItsPeriod) {
  const CubicSpline s(ref()["periodic.x"], ref()["periodic.y"], SplineBoundary::kPeriodic);
  const double period = s.x_max() - s.x_min();
  for (double x = 0.05; x < period; x += 0.4) {
    EXPECT_NEAR(s(x + 3 * period), s(x), 1e-12);
    EXPECT_NEAR(s(x - 2 * period), s(x), 1e-12);
  }
}

// A minimal forward-mode dual number shaped like ceres::Jet (value in .a).
struct Dual {
  double a = 0.0, v = 0.0;
  Dual() = default;
  explicit Dual(double x, double dx = 0.0) : a(x), v(dx) {}
};
Dual operator+(Dual p, Dual q) { return Dual(p.a + q.a, p.v + q.v); }
Dual operator-(Dual p, Dual q) { return Dual(p.a - q.a, p.v - q.v); }
Dual operator*(Dual p, Dual q) { return Dual(p.a * q.a, p.a * q.v + p.v * q.a); }

TEST(CubicSpline, EvaluatesJetLikeScalars) {
  const CubicSpline s(ref()["natural.x"], ref()["natural.y"]);
  for (double x = -0.3; x < 3.3; x += 0.21) {
    const Dual y = s(Dual(x, 1.0));
    EXPECT_NEAR(y.a, s(x), 1e-14);
    EXPECT_NEAR(y.v, s.derivative(x), 1e-12);
  }
}

TEST(CubicSpline, EmptyEvaluatesToZero) {
  const CubicSpline s;
  EXPECT_TRUE(s.empty());
  EXPECT_EQ(s(1.0), 0.0);
  EXPECT_EQ(s.derivative(1.0), 0.0);
}

TEST(CubicSpline, RejectsBadKnots) {
  using V = std::vector<double>;
  EXPECT_THROW(CubicSpline(V{1.0}, V{1.0}), std::invalid_argument);
  EXPECT_THROW(CubicSpline(V{0.0, 1.0}, V{1.0}), std::invalid_argument);
  EXPECT_THROW(CubicSpline(V{0.0, 1.0, 1.0}, V{1.0, 2.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(CubicSpline(V{0.0, 1.0, 2.0}, V{1.0, 2.0, 3.0}, SplineBoundary::kPeriodic),
               std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::model
