// knoblab convert's reshaping of outside arrays (MAT, .npy, .npz) into
// channels: which matrix row or column, or which row of cells, holds which
// channel (--columns t,theta,torque), and segments joined in order.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "knoblab/interchange/mat5.hpp"

namespace knoblab::cli::convert {

enum Channel : std::size_t { kT, kTheta, kOmega, kAlpha, kTorque, kCommand, kChannelCount };
using Channels = std::array<std::vector<double>, kChannelCount>;  // empty = not in the file
constexpr int kSkip = -1;

// One entry per --columns name: the channel's index, or kSkip for '-'.
// Throws UsageError.
std::vector<int> parse_channel_list(const std::string& text);

// A numeric matrix: its rows are the channels if there are as many rows as
// names, else its columns.
Channels from_matrix(const interchange::MatArray& a, const std::vector<int>& cols, const std::string& what);

// A cell array: row k of cells holds channel k, each cell column is one
// segment; segments are appended in order (restart: each segment's clock
// starts again at 0, placed one median interval after the previous one).
Channels from_cells(const interchange::MatArray& a, const std::vector<int>& cols, const std::string& what,
                    bool restart);

// Adds or subtracts whole periods where consecutive values jump by more than
// half of one; returns the number of jumps undone.
std::size_t unwrap(std::vector<double>& x, double period);

}  // namespace knoblab::cli::convert
