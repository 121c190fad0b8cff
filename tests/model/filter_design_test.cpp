// Butterworth and Chebyshev II designs against scipy (tests/reference/
// model_filters.txt) and against their defining properties.
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "knoblab/model/filters.hpp"
#include "reference.hpp"

namespace knoblab::model {
namespace {

struct Design {
  std::string name;  // block prefix in model_filters.txt
  bool butter;
  int order;
  double rs_db;  // cheby2 only
  double edge_hz, fs_hz;
  bool has_sosfilt, has_sosfiltfilt;

  SosCascade make() const {
    return butter ? design_butterworth_lowpass(order, edge_hz, fs_hz)
                  : design_cheby2_lowpass(order, rs_db, edge_hz, fs_hz);
  }
};

// Same list as generate_model_references.py.
const Design kDesigns[] = {
    {"butter1_300_10000", true, 1, 0, 300, 10000, true, false},
    {"butter2_800_10000", true, 2, 0, 800, 10000, false, true},
    {"butter3_1000_10000", true, 3, 0, 1000, 10000, true, true},
    {"butter10_1000_10000", true, 10, 0, 1000, 10000, true, true},
    {"butter20_2000_10000", true, 20, 0, 2000, 10000, true, false},
    {"cheby2_3_20_1000_5000", false, 3, 20, 1000, 5000, true, true},  // Table 6: θ, ω
    {"cheby2_3_20_500_5000", false, 3, 20, 500, 5000, false, true},   // Table 6: α, τ
    {"cheby2_7_40_1500_10000", false, 7, 40, 1500, 10000, true, false},
    {"cheby2_4_30_2000_10000", false, 4, 30, 2000, 10000, false, true},
};

// Readable test names and no byte dumps in ctest's listing.
void PrintTo(const Design& d, std::ostream* os) { *os << d.name; }

const test::Reference& ref() {
  static const test::Reference r("model_filters.txt");
  return r;
}

std::vector<Design> designs_with(bool Design::*flag) {
  std::vector<Design> out;
  for (const Design& d : kDesigns)
    if (!flag || d.*flag) out.push_back(d);
  return out;
}

std::string design_name(const ::testing::TestParamInfo<Design>& param_info) {
  return param_info.param.name;
}

class ScipyResponse : public ::testing::TestWithParam<Design> {};
class ScipySosfilt : public ::testing::TestWithParam<Design> {};
class ScipySosfiltfilt : public ::testing::TestWithParam<Design> {};

TEST_P(ScipyResponse, Matches) {
  const Design& d = GetParam();
  const SosCascade f = d.make();
  const std::vector<double>& freqs = ref()["freqs_fs5000"];
  const std::vector<double>& h = ref()[d.name + ".freqz"];
  for (std::size_t i = 0; i < freqs.size(); ++i) {
    const std::complex<double> got = f.response(freqs[i] / 5000.0 * d.fs_hz, d.fs_hz);
    EXPECT_NEAR(got.real(), h[2 * i], 1e-10) << "f index " << i;
    EXPECT_NEAR(got.imag(), h[2 * i + 1], 1e-10) << "f index " << i;
  }
}

TEST_P(ScipySosfilt, Matches) {
  const Design& d = GetParam();
  const std::vector<double> y = sosfilt(d.make(), ref()["input"]);
  EXPECT_LT(test::relative_max_error(y, ref()[d.name + ".sosfilt"]), 1e-9);
}

TEST_P(ScipySosfiltfilt, Matches) {
  const Design& d = GetParam();
  const std::vector<double> y = sosfiltfilt(d.make(), ref()["input"]);
  EXPECT_LT(test::relative_max_error(y, ref()[d.name + ".sosfiltfilt"]), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Filters, ScipyResponse, ::testing::ValuesIn(designs_with(nullptr)),
                         design_name);
INSTANTIATE_TEST_SUITE_P(Filters, ScipySosfilt,
                         ::testing::ValuesIn(designs_with(&Design::has_sosfilt)), design_name);
INSTANTIATE_TEST_SUITE_P(Filters, ScipySosfiltfilt,
                         ::testing::ValuesIn(designs_with(&Design::has_sosfiltfilt)), design_name);

TEST(Butterworth, EveryOrderIsMinus3dBAtCutoffAndUnityAtDc) {
  for (int n = 1; n <= 20; ++n) {
    const SosCascade f = design_butterworth_lowpass(n, 1000.0, 10000.0);
    EXPECT_EQ(f.size(), static_cast<std::size_t>((n + 1) / 2)) << n;
    EXPECT_NEAR(f.dc_gain(), 1.0, 1e-12) << n;
    EXPECT_NEAR(std::abs(f.response(1000.0, 10000.0)), std::sqrt(0.5), 1e-10) << n;
    // Maximally flat and monotone: |H| falls with frequency (to rounding).
    double last = 1.0;
    for (double fr = 0.0; fr < 5000.0; fr += 97.0) {
      const double mag = std::abs(f.response(fr, 10000.0));
      EXPECT_LE(mag, last + 1e-13) << "order " << n << " at " << fr << " Hz";
      last = mag;
    }
  }
}

TEST(Cheby2, EveryOrderMeetsStopBandAndUnityAtDc) {
  for (int n = 1; n <= 20; ++n) {
    const double rs = 20.0 + n;  // vary the attenuation too
    const SosCascade f = design_cheby2_lowpass(n, rs, 1000.0, 10000.0);
    const double stop = std::pow(10.0, -rs / 20.0);
    EXPECT_NEAR(f.dc_gain(), 1.0, 1e-10) << n;
    EXPECT_NEAR(std::abs(f.response(1000.0, 10000.0)), stop, 1e-9) << n;
    for (double fr = 1000.0; fr < 5000.0; fr += 37.0)
      EXPECT_LE(std::abs(f.response(fr, 10000.0)), stop * (1.0 + 1e-9)) << n << " " << fr;
  }
}

// Closed-form magnitudes of the bilinear-transformed designs, with the
// prewarped frequency Ω = tan(π·f/fs):
//   Butterworth  |H|² = 1 / (1 + (Ω/Ωc)^(2n))
//   Chebyshev II |H|² = ε²T_n²(Ωs/Ω) / (1 + ε²T_n²(Ωs/Ω)),  ε² = 1/(10^(rs/10) − 1)
double chebyshev_t(int n, double x) {
  return std::abs(x) <= 1.0 ? std::cos(n * std::acos(x)) : std::cosh(n * std::acosh(std::abs(x)));
}

TEST(FilterDesign, MagnitudeMatchesClosedFormForAllOrdersAndEdges) {
  const double fs = 10000.0;
  const double kPi = std::acos(-1.0);
  for (int n = 1; n <= 20; ++n) {
    for (const double edge : {10.0, 1000.0, 4500.0}) {
      const SosCascade butter = design_butterworth_lowpass(n, edge, fs);
      const SosCascade cheby = design_cheby2_lowpass(n, 35.0, edge, fs);
      const double eps2 = 1.0 / (std::pow(10.0, 3.5) - 1.0);
      const double wc = std::tan(kPi * edge / fs);
      for (const double fr : {1.0, 0.5 * edge, 0.97 * edge, 1.3 * edge, 4900.0}) {
        if (fr >= fs / 2) continue;
        const double w = std::tan(kPi * fr / fs);
        const double b2 = 1.0 / (1.0 + std::pow(w / wc, 2.0 * n));
        EXPECT_NEAR(std::norm(butter.response(fr, fs)), b2, 1e-9)
            << "butter n=" << n << " edge=" << edge << " f=" << fr;
        const double t2 = eps2 * std::pow(chebyshev_t(n, wc / w), 2.0);
        EXPECT_NEAR(std::norm(cheby.response(fr, fs)), t2 / (1.0 + t2), 1e-9)
            << "cheby2 n=" << n << " edge=" << edge << " f=" << fr;
      }
    }
  }
}

TEST(Cheby2, ThesisTable6FiltersAreDown20dBAtTheirEdges) {
  for (const double edge : {1000.0, 500.0}) {
    const SosCascade f = design_cheby2_lowpass(3, 20.0, edge, 5000.0);
    EXPECT_NEAR(20.0 * std::log10(std::abs(f.response(edge, 5000.0))), -20.0, 1e-9);
  }
}

TEST(FilterDesign, RejectsBadArguments) {
  EXPECT_THROW(design_butterworth_lowpass(0, 100.0, 1000.0), std::invalid_argument);
  EXPECT_THROW(design_butterworth_lowpass(21, 100.0, 1000.0), std::invalid_argument);
  EXPECT_THROW(design_butterworth_lowpass(2, 500.0, 1000.0), std::invalid_argument);
  EXPECT_THROW(design_butterworth_lowpass(2, 0.0, 1000.0), std::invalid_argument);
  EXPECT_THROW(design_cheby2_lowpass(3, 0.0, 100.0, 1000.0), std::invalid_argument);
  EXPECT_THROW(design_cheby2_lowpass(3, 20.0, 600.0, 1000.0), std::invalid_argument);
}

TEST(Sosfiltfilt, PadlenIsScipys) {
  // 3·(2·sections + 1 − first-order sections)
  EXPECT_EQ(sosfiltfilt_padlen(design_butterworth_lowpass(3, 1000, 10000)), 12u);
  EXPECT_EQ(sosfiltfilt_padlen(design_butterworth_lowpass(10, 1000, 10000)), 33u);
  EXPECT_EQ(sosfiltfilt_padlen(design_cheby2_lowpass(3, 20, 1000, 5000)), 12u);
  EXPECT_EQ(sosfiltfilt_padlen(design_cheby2_lowpass(4, 20, 1000, 5000)), 15u);
}

}  // namespace
}  // namespace knoblab::model
