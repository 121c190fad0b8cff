#include <gtest/gtest.h>

#include <thread>

#include "knoblab/hapticd/latest.hpp"

namespace knoblab::hapticd {
namespace {

struct Pair {
  long a = 0, b = 0;  // always written equal: a torn read would show a != b
};

TEST(Latest, TakesOnlyFreshValuesAndTheNewestOne) {
  Latest<Pair> l;
  Pair p;
  EXPECT_FALSE(l.take(p));
  l.publish({1, 1});
  l.publish({2, 2});
  ASSERT_TRUE(l.take(p));
  EXPECT_EQ(p.a, 2);
  EXPECT_FALSE(l.take(p));
  l.publish({3, 3});
  ASSERT_TRUE(l.take(p));
  EXPECT_EQ(p.a, 3);
}

TEST(Latest, ConcurrentReaderNeverSeesATornOrOlderValue) {
  Latest<Pair> l;
  constexpr long kN = 2'000'000;
  std::thread writer([&] {
    for (long i = 1; i <= kN; ++i) l.publish({i, i});
  });
  long last = 0;
  Pair p;
  while (last < kN) {
    if (!l.take(p)) continue;
    ASSERT_EQ(p.a, p.b);
    ASSERT_GT(p.a, last);
    last = p.a;
  }
  writer.join();
}

}  // namespace
}  // namespace knoblab::hapticd
