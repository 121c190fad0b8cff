// Average ranks and the tie term every tie correction uses.
#include <gtest/gtest.h>

#include "knoblab/stats/ranks.hpp"

namespace knoblab::stats {
namespace {

TEST(Ranks, TiesShareTheirMeanRank) {
  const std::vector<double> v = {7, 3, 7, 1, 3, 3, 9};
  const Ranking r = rank_average(v);
  EXPECT_EQ(r.ranks, (std::vector<double>{5.5, 3, 5.5, 1, 3, 3, 7}));
  EXPECT_EQ(r.tie_sizes, (std::vector<double>{3, 2}));
  EXPECT_EQ(r.tie_term(), (27 - 3) + (8 - 2));
}

TEST(Ranks, EmptyAndUntiedInputs) {
  EXPECT_TRUE(rank_average({}).ranks.empty());
  const std::vector<double> v = {0.2, -1, 4};
  const Ranking r = rank_average(v);
  EXPECT_EQ(r.ranks, (std::vector<double>{2, 1, 3}));
  EXPECT_EQ(r.tie_term(), 0);
}

}  // namespace
}  // namespace knoblab::stats
