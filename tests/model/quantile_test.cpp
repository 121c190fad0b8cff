// model::quantile: the order statistic at ⌊q·(n − 1)⌋, no interpolation.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "knoblab/model/quantile.hpp"

namespace knoblab::model {
namespace {

TEST(Quantile, IsTheOrderStatisticAtTheFloorOfQTimesNMinusOne) {
  const std::vector<double> v{5, 1, 4, 2, 3};
  EXPECT_EQ(quantile(v, 0.0), 1.0);
  EXPECT_EQ(quantile(v, 0.5), 3.0);
  EXPECT_EQ(quantile(v, 0.74), 3.0);  // ⌊0.74·4⌋ = 2: no interpolation toward 4
  EXPECT_EQ(quantile(v, 0.75), 4.0);
  EXPECT_EQ(quantile(v, 1.0), 5.0);
  EXPECT_EQ(quantile({1, 2, 3, 4}, 0.5), 2.0);  // even n: the lower median
}

TEST(Quantile, OfNothingIsNaN) { EXPECT_TRUE(std::isnan(quantile({}, 0.5))); }

}  // namespace
}  // namespace knoblab::model
