// Is a candidate's held-out improvement consistent over the held-out time
// blocks? Each block gives a drop, log(MSE before / MSE after): relative, so
// blocks with large errors (reversal transients) do not carry an effect.
//
//   drop_consistency(drops) ≥ 3  ⇒  the drop is there in most blocks
//
// The larger of two one-sided tests that the drops are above zero: the t of
// their mean, and the Wilcoxon signed-rank z. One block with a very large
// drop (a breakaway the effect explains) inflates the spread and sinks the
// t; the signed ranks count it as one block that improved.
#pragma once

#include <span>

namespace knoblab::discovery {

// One-sample t of the mean against 0 (0 with fewer than two drops; a large
// number when every drop is the same positive value).
double mean_t(std::span<const double> drops);

// Wilcoxon signed-rank z (normal approximation, tied |drops| share their
// mean rank, zero drops left out; 0 with fewer than two non-zero drops).
double signed_rank_z(std::span<const double> drops);

// max(mean_t, signed_rank_z).
double drop_consistency(std::span<const double> drops);

}  // namespace knoblab::discovery
