// The quantiles behind every confidence interval the fits report, against
// table values (SciPy's norm.ppf / t.ppf, which agree with the printed tables
// to their 4–5 digits).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "knoblab/fit/stats.hpp"

namespace knoblab::fit {
namespace {

TEST(Stats, NormalQuantileMatchesTables) {
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-12);
  EXPECT_NEAR(normal_quantile(0.5), 0.0, 1e-15);
  EXPECT_NEAR(normal_quantile(0.8413447460685429), 1.0, 1e-12);  // Φ(1)
  EXPECT_NEAR(normal_quantile(0.995), 2.5758293035489004, 1e-12);
  // Deep in the tails (Acklam's outer region).
  EXPECT_NEAR(normal_quantile(1e-10), -6.361340902404056, 1e-9);
  EXPECT_NEAR(normal_quantile(0.01), -2.3263478740408408, 1e-12);
  // The upper tail as precisely as the lower (1 − 2⁻³³ is exact).
  EXPECT_NEAR(normal_quantile(1 - std::ldexp(1.0, -33)), 6.3379577545537895, 1e-12);
  EXPECT_NEAR(normal_quantile(std::ldexp(1.0, -13)), -3.6683292851213234, 1e-12);
}

TEST(Stats, StudentTQuantileMatchesTables) {
  // The two-sided 95% factor t(0.975, dof): the 4-digit table values …
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062, 5e-5);
  EXPECT_NEAR(student_t_quantile(0.975, 2), 4.3027, 5e-5);
  EXPECT_NEAR(student_t_quantile(0.975, 5), 2.5706, 5e-5);
  EXPECT_NEAR(student_t_quantile(0.975, 10), 2.2281, 5e-5);
  EXPECT_NEAR(student_t_quantile(0.975, 63), 1.9983, 5e-5);
  EXPECT_NEAR(student_t_quantile(0.975, 1e6), 1.959966, 5e-7);
  // … and to 1e-9 relative, small dof included (where a series about the
  // normal quantile is off in the 3rd digit).
  struct Row {
    double p, dof, t;
  };
  for (const Row& r : {Row{0.975, 1, 12.706204736432095}, Row{0.975, 2, 4.302652729696142},
                       Row{0.975, 3, 3.182446305284263}, Row{0.975, 4, 2.7764451051977987},
                       Row{0.975, 5, 2.570581835636314}, Row{0.975, 10, 2.2281388519649385},
                       Row{0.975, 30, 2.0422724563012373}, Row{0.975, 63, 1.998340542520741},
                       Row{0.975, 1e5, 1.9599877075346093}, Row{0.975, 2e5, 1.959975845966768},
                       Row{0.975, 1e6, 1.9599663568141066}, Row{0.995, 7, 3.4994832973505026},
                       Row{0.9, 3, 1.6377443536962095}, Row{0.999, 5, 5.8934295313560074},
                       Row{0.6, 4, 0.2707222947059493}}) {
    EXPECT_NEAR(student_t_quantile(r.p, r.dof), r.t, 1e-9 * r.t) << "p " << r.p << " dof " << r.dof;
  }
}

TEST(Stats, StudentTQuantileForRealDofAndFarTails) {
  // Welch–Satterthwaite dof are not whole numbers.
  EXPECT_NEAR(student_t_quantile(0.975, 1.5), 6.016663104427928, 1e-9 * 6.0);
  EXPECT_NEAR(student_t_quantile(0.975, 2.5), 3.5746548420118773, 1e-9 * 3.6);
  // Heavy tails: far out, the quantile runs to thousands (and millions).
  EXPECT_NEAR(student_t_quantile(1e-10, 3), -2225.769284683086, 1e-9 * 2225.8);
  EXPECT_NEAR(student_t_quantile(1e-10, 1.5), -2422663.1011343612, 1e-8 * 2422663.1);
  // Between the table rows it falls monotonically towards the normal quantile.
  double prev = std::numeric_limits<double>::infinity();
  for (double dof = 1.0; dof < 1e7; dof *= 1.37) {
    const double t = student_t_quantile(0.975, dof);
    EXPECT_LT(t, prev) << dof;
    EXPECT_GT(t, normal_quantile(0.975)) << dof;
    prev = t;
  }
  EXPECT_NEAR(student_t_quantile(0.975, std::numeric_limits<double>::infinity()), normal_quantile(0.975), 1e-15);
}

TEST(Stats, QuantilesAreSymmetric) {
  // 2⁻³³ and 2⁻¹³: 1 − p is exact, so the far tail is compared fairly.
  for (double p : {std::ldexp(1.0, -33), std::ldexp(1.0, -13), 0.01, 0.025, 0.1, 0.3, 0.45}) {
    EXPECT_NEAR(normal_quantile(p), -normal_quantile(1 - p), 1e-12) << p;
    for (double dof : {1.0, 2.0, 3.0, 5.0, 7.5, 63.0, 1e6})
      EXPECT_NEAR(student_t_quantile(p, dof), -student_t_quantile(1 - p, dof),
                  1e-9 * std::abs(student_t_quantile(p, dof)) + 1e-12)
          << p << " " << dof;
  }
  EXPECT_DOUBLE_EQ(student_t_quantile(0.5, 4), 0.0);
}

TEST(Stats, Ci95HalfWidthIsTTimesTheStandardError) {
  EXPECT_NEAR(ci95_half_width(2.0, 5), 2 * 2.570581835636314, 1e-9);
  EXPECT_NEAR(ci95_half_width(0.5, 1), 0.5 * 12.706204736432095, 1e-9);
  EXPECT_DOUBLE_EQ(ci95_half_width(0.0, 10), 0.0);
}

TEST(Stats, OutsideTheDomainIsAnError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double p : {0.0, 1.0, -0.1, 1.1, nan}) {
    EXPECT_THROW(normal_quantile(p), std::domain_error) << p;
    EXPECT_THROW(student_t_quantile(p, 5), std::domain_error) << p;
  }
  for (double dof : {0.0, 0.5, -1.0, nan}) {
    EXPECT_THROW(student_t_quantile(0.975, dof), std::domain_error) << dof;
    EXPECT_THROW(ci95_half_width(1.0, dof), std::domain_error) << dof;
  }
}

}  // namespace
}  // namespace knoblab::fit
