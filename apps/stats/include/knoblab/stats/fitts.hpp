// Rotary Fitts' law (thesis §4.6.2, Study 3). Amplitudes, widths and
// end-points are angles in one unit (degrees or radians); movement times in
// one unit of time.
//
// The thesis uses Welford's index of difficulty (Eq. 18) with the nominal
// target width, and reports each condition's end-point variance (Table 27)
// as its "effective target width"; it computes no throughput. The
// effective-width throughput below is the ISO 9241-9 form (MacKenzie),
// which the thesis does not use, for the appliance's own pointing studies.
#pragma once

#include <cstddef>
#include <span>

namespace knoblab::stats {

// Eq. 18: ID = log_b(A/W + 0.5). The thesis writes "log" without a base;
// its Table 27 values (1.3 for 30°/1.4°, 0.5 for 30°/11.3°) are base 10,
// Welford's own form is base 2 (bits). r² of an MT–ID line does not depend
// on the base. Throws std::invalid_argument unless A > 0, W > 0, b > 1.
double welford_index_of_difficulty(double amplitude, double width, double log_base);

struct EndpointSpread {
  double mean = 0;
  double sd = 0;        // sample standard deviation (n − 1)
  double variance = 0;  // sd², Table 27's σ²
  std::size_t n = 0;
};

// End-points of one amplitude/width condition, each measured along its
// movement's direction (so that movements to either side pool: e.g. the
// signed overshoot past the target centre). Needs n ≥ 2 finite values.
EndpointSpread endpoint_spread(std::span<const double> endpoints);

// The ISO 9241-9 constant: We = 4.133·SD covers 96 % of a normal spread
// (4.133 ≈ √(2πe), the width whose uniform distribution has the normal's
// entropy).
inline constexpr double kEffectiveWidthPerSd = 4.133;

struct EffectiveThroughput {
  double effective_width = 0;       // We = 4.133·SD(end-points)
  double index_of_difficulty = 0;   // IDe = log2(A/We + 1), bits
  double mean_movement_time = 0;
  double throughput = 0;            // IDe / mean MT, bits per unit of time
};

// One amplitude/width condition's throughput. `amplitude` is the nominal A,
// or the mean distance actually moved (the effective amplitude Ae) if the
// caller prefers ISO's stricter form. Needs ≥ 2 end-points with some spread,
// ≥ 1 movement time, all finite, times > 0, A > 0.
EffectiveThroughput effective_throughput(double amplitude, std::span<const double> endpoints,
                                         std::span<const double> movement_times);

struct LineFit {
  double intercept = 0;  // a
  double slope = 0;      // b
  double r_squared = 0;
  std::size_t n = 0;
};

// Least squares MT = a + b·ID (Figures 61 and 62). Needs n ≥ 2 finite
// pairs, neither ID nor MT constant (b or r² would be undefined).
LineFit fit_line(std::span<const double> index_of_difficulty, std::span<const double> movement_time);

}  // namespace knoblab::stats
