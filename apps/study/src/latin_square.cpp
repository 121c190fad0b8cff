#include "knoblab/study/latin_square.hpp"

#include <algorithm>
#include <stdexcept>

namespace knoblab::study {

std::size_t williams_rows(std::size_t n) {
  if (n == 0) throw std::invalid_argument("a Latin square needs at least one level");
  return n % 2 == 0 || n == 1 ? n : 2 * n;
}

std::vector<std::size_t> williams_row(std::size_t n, std::size_t row) {
  row %= williams_rows(n);
  // First row 0, 1, n−1, 2, n−2, …: its successive differences are
  // +1, −2, +3, −4, … (mod n), all distinct for even n, so each shifted copy
  // adds every ordered pair exactly once.
  std::vector<std::size_t> order(n);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t first = j == 0 ? 0 : j % 2 == 1 ? (j + 1) / 2 : n - j / 2;
    order[j] = (first + row % n) % n;
  }
  // For odd n the differences repeat in pairs; the mirrored rows supply each
  // pair's other half.
  if (row >= n) std::reverse(order.begin(), order.end());
  return order;
}

std::vector<std::vector<std::size_t>> williams_square(std::size_t n) {
  std::vector<std::vector<std::size_t>> rows;
  for (std::size_t r = 0; r < williams_rows(n); ++r) rows.push_back(williams_row(n, r));
  return rows;
}

}  // namespace knoblab::study
