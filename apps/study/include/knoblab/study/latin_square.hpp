// Balanced Latin squares (Williams designs) for counterbalancing the order
// of a factor's levels across participants. Across all rows, every level
// sits in every position equally often and immediately precedes every other
// level equally often, so first-order carry-over effects balance out. For
// an even number of levels n the square has n rows (each ordered pair once);
// for odd n no n-row square does that, and the square is the n rows of the
// cyclic construction followed by their n mirror images (each pair twice).
#pragma once

#include <cstddef>
#include <vector>

namespace knoblab::study {

// n for even n (and for n = 1), 2n for odd n > 1. Throws
// std::invalid_argument for n = 0.
std::size_t williams_rows(std::size_t n);

// Row `row % williams_rows(n)`: a permutation of 0 … n−1. Row r (r < n) is
// the first row 0, 1, n−1, 2, n−2, … with r added to each entry mod n; for
// odd n, row n + r is row r reversed.
std::vector<std::size_t> williams_row(std::size_t n, std::size_t row);

// All rows, in order.
std::vector<std::vector<std::size_t>> williams_square(std::size_t n);

}  // namespace knoblab::study
