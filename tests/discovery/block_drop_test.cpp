// drop_consistency: is a held-out improvement there in most time blocks?
#include <gtest/gtest.h>

#include <vector>

#include "knoblab/discovery/block_drop.hpp"

namespace knoblab::discovery {
namespace {

TEST(BlockDrop, SignedRankZMatchesScipyWithTies) {
  // scipy.stats.wilcoxon(x, correction=False, method='approx',
  // alternative='greater'): W+ 61, p 0.04153 → z = norm.isf(p) = 1.73317.
  const std::vector<double> x{0.3, -0.1, 0.2, 0.2, 0.5, -0.4, 0.1, 0.6, 0.2, -0.2, 0.7, 0.05};
  EXPECT_NEAR(signed_rank_z(x), 1.7331702097, 1e-9);
}

TEST(BlockDrop, OneVeryLargeBlockSinksTheTButNotTheSignedRanks) {
  // Every block improves, one by far the most (a breakaway the effect
  // explains): the spread it adds keeps the t at 1.56 (scipy ttest_1samp),
  // the signed ranks see 16 of 16 blocks better, z 3.52.
  std::vector<double> x;
  for (int k = 0; k < 15; ++k) x.push_back(0.08 + 0.005 * k);
  x.push_back(3.4);
  EXPECT_NEAR(mean_t(x), 1.5595823056, 1e-9);
  EXPECT_NEAR(signed_rank_z(x), 3.5161962920, 1e-9);
  EXPECT_GE(drop_consistency(x), 3.0);
}

TEST(BlockDrop, DropsOfEitherSignAreNotConsistent) {
  std::vector<double> x;
  for (int k = 0; k < 16; ++k) x.push_back(k % 2 ? 0.1 + 0.01 * k : -0.1 - 0.01 * k);
  EXPECT_LT(drop_consistency(x), 1.0);
  // One block in the wrong direction, the largest: t and z both fall.
  std::vector<double> y(15, 0.1);
  y.push_back(-3.0);
  EXPECT_LT(drop_consistency(y), 3.0);
}

TEST(BlockDrop, TooFewDropsSayNothing) {
  EXPECT_EQ(drop_consistency(std::vector<double>{}), 0.0);
  EXPECT_EQ(drop_consistency(std::vector<double>{0.5}), 0.0);
  EXPECT_EQ(signed_rank_z(std::vector<double>{0.0, 0.0, 0.4}), 0.0);
}

}  // namespace
}  // namespace knoblab::discovery
