// load_tiles' stable ranges (apps/hapticd/src/stable_range.hpp): which points
// are settled by the range and which still need an eigenvalue problem.
#include <gtest/gtest.h>

#include <limits>

#include "../../apps/hapticd/src/stable_range.hpp"

namespace knoblab::hapticd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The test a point would otherwise need; counts how often it is asked.
struct CountedTest {
  int asked = 0;
  bool answer = true;
  bool operator()() { return ++asked, answer; }
};

TEST(StableRange, APointWellInsideIsStableWithoutATestOfItsOwn) {
  CountedTest t;
  EXPECT_TRUE((StableRange{-2.0, 711.0}.holds(300.0, t)));
  EXPECT_FALSE((StableRange{-2.0, 711.0}.holds(800.0, t)));
  EXPECT_FALSE((StableRange{-2.0, 711.0}.holds(-3.0, t)));
  EXPECT_EQ(t.asked, 0);
}

TEST(StableRange, APointAtAnEndIsTested) {
  CountedTest t{.asked = 0, .answer = false};
  EXPECT_FALSE((StableRange{-2.0, 711.0}.holds(711.0, t)));
  EXPECT_EQ(t.asked, 1);
}

TEST(StableRange, AnInfiniteEndStillSettlesThePointsInside) {
  // At a 1 kHz loop no fall of a detent is steep enough to ring: the least
  // stable stiffness is −∞. Scaled by it the margin was infinite, and every
  // point of a tile went to its own test (seconds for a design, past the
  // client's watchdog).
  CountedTest t;
  EXPECT_TRUE((StableRange{-kInf, 711.0}.holds(-5e4, t)));
  EXPECT_TRUE((StableRange{-kInf, 711.0}.holds(0.0, t)));
  EXPECT_FALSE((StableRange{-kInf, 711.0}.holds(800.0, t)));
  EXPECT_TRUE((StableRange{0.0, kInf}.holds(1e6, t)));
  EXPECT_EQ(t.asked, 0);
}

TEST(StableRange, AnEmptyRangeHoldsNothing) {
  CountedTest t;
  EXPECT_FALSE(StableRange{}.holds(0.0, t));
  EXPECT_EQ(t.asked, 0);
}

}  // namespace
}  // namespace knoblab::hapticd
