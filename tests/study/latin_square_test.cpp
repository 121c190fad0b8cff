// Williams squares: each row a permutation; across the rows every level takes
// every position equally often and immediately precedes every other level
// equally often (once for even n, twice for odd n), for even and odd n.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "knoblab/study/latin_square.hpp"

namespace knoblab::study {
namespace {

TEST(WilliamsSquare, EvenSizesHaveNRowsAndOddSizesTwice) {
  EXPECT_EQ(williams_rows(1), 1u);
  EXPECT_EQ(williams_rows(2), 2u);
  EXPECT_EQ(williams_rows(3), 6u);
  EXPECT_EQ(williams_rows(4), 4u);
  EXPECT_EQ(williams_rows(7), 14u);
  EXPECT_THROW(williams_rows(0), std::invalid_argument);
}

TEST(WilliamsSquare, TheFirstRowAlternatesFromBothEnds) {
  EXPECT_EQ(williams_row(4, 0), (std::vector<std::size_t>{0, 1, 3, 2}));
  EXPECT_EQ(williams_row(4, 1), (std::vector<std::size_t>{1, 2, 0, 3}));
  EXPECT_EQ(williams_row(5, 0), (std::vector<std::size_t>{0, 1, 4, 2, 3}));
  EXPECT_EQ(williams_row(5, 5), (std::vector<std::size_t>{3, 2, 4, 1, 0}));  // row 0 mirrored
}

TEST(WilliamsSquare, RowsRepeatAfterTheSquare) {
  for (std::size_t n : {4u, 5u})
    for (std::size_t r = 0; r < williams_rows(n); ++r)
      EXPECT_EQ(williams_row(n, r), williams_row(n, r + williams_rows(n)));
}

TEST(WilliamsSquare, EveryRowIsAPermutation) {
  for (std::size_t n = 1; n <= 12; ++n)
    for (const auto& row : williams_square(n)) {
      std::vector<std::size_t> sorted = row;
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::size_t> identity(n);
      std::iota(identity.begin(), identity.end(), 0u);
      EXPECT_EQ(sorted, identity) << "n = " << n;
    }
}

TEST(WilliamsSquare, EachLevelTakesEachPositionEquallyOften) {
  for (std::size_t n = 1; n <= 12; ++n) {
    const auto square = williams_square(n);
    const std::size_t times = square.size() / n;
    for (std::size_t level = 0; level < n; ++level)
      for (std::size_t pos = 0; pos < n; ++pos) {
        std::size_t count = 0;
        for (const auto& row : square) count += row[pos] == level;
        EXPECT_EQ(count, times) << "n = " << n << ", level " << level << ", position " << pos;
      }
  }
}

TEST(WilliamsSquare, EachLevelPrecedesEachOtherLevelEquallyOftenForEvenAndOddSizes) {
  for (std::size_t n = 2; n <= 12; ++n) {
    std::vector<std::vector<std::size_t>> follows(n, std::vector<std::size_t>(n, 0));
    for (const auto& row : williams_square(n))
      for (std::size_t j = 0; j + 1 < n; ++j) ++follows[row[j]][row[j + 1]];
    const std::size_t expected = n % 2 == 0 ? 1 : 2;
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b)
        EXPECT_EQ(follows[a][b], a == b ? 0 : expected) << "n = " << n << ": " << a << " before " << b;
  }
}

}  // namespace
}  // namespace knoblab::study
