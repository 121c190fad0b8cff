// The matching sliders' power-law mapping (Stevens, thesis §3.4.3.3): slider
// position → SI value and back, and the protocol key that sets its exponent.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "examples.hpp"
#include "knoblab/study/slider_mapping.hpp"

namespace knoblab::study {
namespace {

using nlohmann::json;
using test::example;
using test::example_json;

// Table 11's damping slider, 0 → 30 mN·m/(rad/s), with exponent β.
Slider damping(double beta) { return {.parameter = "B_vel", .min = 0, .max = 30e-3, .perceptual_exponent = beta}; }

TEST(SliderMapping, AnExponentOfOneIsTheLinearSlider) {
  const Slider s{.parameter = "M_acc", .min = 0.1e-3, .max = 0.75e-3};
  EXPECT_EQ(s.perceptual_exponent, 1.0);
  for (const double p : {0.0, 0.1, 0.25, 0.5, 0.8, 1.0}) {
    EXPECT_DOUBLE_EQ(slider_value(s, p), 0.1e-3 + 0.65e-3 * p) << p;
    EXPECT_NEAR(slider_position(s, 0.1e-3 + 0.65e-3 * p), p, 1e-15) << p;
  }
}

TEST(SliderMapping, AnExponentOfOneHalfSquaresThePosition) {
  // ψ ∝ φ^0.5: half the perceived range is a quarter of the values' range.
  const Slider s{.parameter = "A_pos", .min = 2e-3, .max = 12e-3, .perceptual_exponent = 0.5};
  for (const double p : {0.0, 0.2, 0.5, 0.7, 1.0}) EXPECT_NEAR(slider_value(s, p), 2e-3 + 10e-3 * p * p, 1e-15) << p;
  EXPECT_NEAR(slider_value(s, 0.5), 4.5e-3, 1e-15);
  EXPECT_NEAR(slider_position(s, 4.5e-3), 0.5, 1e-12);
  // β = 2 the other way round: the square root.
  EXPECT_NEAR(slider_value(damping(2), 0.25), 15e-3, 1e-15);
  EXPECT_NEAR(slider_position(damping(2), 15e-3), 0.25, 1e-15);
}

TEST(SliderMapping, EqualSliderStepsAreEqualStepsOfPerceivedMagnitude) {
  // ψ = φ^β: every tenth of the slider adds the same ψ.
  const double beta = 0.42;
  const Slider s = damping(beta);
  double last = 0;
  for (int k = 1; k <= 10; ++k) {
    const double psi = std::pow(slider_value(s, k / 10.0), beta);
    if (k > 1) {
      EXPECT_NEAR(psi - last, std::pow(s.max, beta) / 10, 1e-12) << k;
    }
    last = psi;
  }
}

TEST(SliderMapping, PositionToValueToPositionComesBackForEveryExponent) {
  // From 0, as the thesis' sliders: the value keeps its relative precision
  // at the bottom however steep the curve (above a bottom of 1, p = 0.05 at
  // β = 0.1 is 1 + 3·10⁻¹², and a double keeps only 4 digits of the 3).
  for (const double beta : {0.1, 0.33, 0.5, 1.0, 1.45, 3.5, 10.0}) {
    const Slider s{.parameter = "detents_per_rev", .min = 0, .max = 32, .perceptual_exponent = beta};
    for (int k = 0; k <= 20; ++k) {
      const double p = k / 20.0;
      const double v = slider_value(s, p);
      EXPECT_GE(v, s.min);
      EXPECT_LE(v, s.max);
      EXPECT_NEAR(slider_position(s, v), p, 1e-9) << "β " << beta << ", position " << p;
    }
    EXPECT_EQ(slider_value(s, 0), s.min);
    EXPECT_EQ(slider_value(s, 1), s.max);
  }
  for (const double beta : {0.5, 0.8, 1.25, 2.0}) {
    const Slider s{.parameter = "detents_per_rev", .min = 1, .max = 32, .perceptual_exponent = beta};
    for (int k = 0; k <= 20; ++k) EXPECT_NEAR(slider_position(s, slider_value(s, k / 20.0)), k / 20.0, 1e-12) << beta;
  }
}

TEST(SliderMapping, OutOfRangeIsClampedAndNonFiniteIsRefused) {
  const Slider s = damping(0.5);
  EXPECT_EQ(slider_value(s, -0.5), 0.0);
  EXPECT_EQ(slider_value(s, 1.5), 30e-3);
  EXPECT_EQ(slider_position(s, -1.0), 0.0);
  EXPECT_EQ(slider_position(s, 1.0), 1.0);
  EXPECT_THROW(slider_value(s, std::nan("")), std::invalid_argument);
  EXPECT_THROW(slider_value(s, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(slider_position(s, std::nan("")), std::invalid_argument);
  // A slider made in code without a valid exponent or range has no mapping.
  EXPECT_THROW(slider_value(damping(0), 0.5), std::invalid_argument);
  EXPECT_THROW(slider_value(damping(-1), 0.5), std::invalid_argument);
  EXPECT_THROW(slider_position(damping(std::nan("")), 0.01), std::invalid_argument);
  EXPECT_THROW(slider_value(Slider{.parameter = "B_vel", .min = 1, .max = 1}, 0.5), std::invalid_argument);
}

// The error parsing `file`: its path and message.
std::pair<std::string, std::string> refusal(const json& file) {
  try {
    parse_protocol(file);
  } catch (const ProtocolError& e) {
    return {e.path(), e.message()};
  }
  ADD_FAILURE() << "the protocol was accepted";
  return {};
}

TEST(SliderMapping, TheProtocolGivesEachSliderItsExponentOrLinear) {
  json file = example_json("matching-novice.json");
  file["matching"]["sliders"][1]["perceptual_exponent"] = 0.42;
  const Protocol p = parse_protocol(file);
  const auto& m = std::get<MatchingSettings>(p.settings);
  EXPECT_EQ(m.sliders[0].perceptual_exponent, 1.0);
  EXPECT_EQ(m.sliders[1].perceptual_exponent, 0.42);
  // The examples keep the thesis' linear sliders.
  for (const char* name : {"matching-novice.json", "matching-expert.json"}) {
    const Protocol example_protocol = example(name);
    for (const Slider& s : std::get<MatchingSettings>(example_protocol.settings).sliders)
      EXPECT_EQ(s.perceptual_exponent, 1.0) << name << " " << s.parameter;
  }
}

TEST(SliderMapping, AnExponentThatIsNotAPositiveNumberIsRefusedAtItsPath) {
  const std::string path = "matching.sliders[2].perceptual_exponent";
  for (const json& bad : {json(0), json(-0.5)}) {
    json file = example_json("matching-novice.json");
    file["matching"]["sliders"][2]["perceptual_exponent"] = bad;
    const auto [at, message] = refusal(file);
    EXPECT_EQ(at, path) << bad;
    EXPECT_NE(message.find("above 0"), std::string::npos) << message;
  }
  for (const json& bad : {json(0.05), json(11)}) {
    json file = example_json("matching-novice.json");
    file["matching"]["sliders"][2]["perceptual_exponent"] = bad;
    const auto [at, message] = refusal(file);
    EXPECT_EQ(at, path) << bad;
    EXPECT_NE(message.find("from 0.1 to 10"), std::string::npos) << message;
  }
  json file = example_json("matching-novice.json");
  file["matching"]["sliders"][2]["perceptual_exponent"] = "0.5";
  const auto [at, message] = refusal(file);
  EXPECT_EQ(at, path);
  EXPECT_NE(message.find("expected a number"), std::string::npos) << message;
  // what() says where and why, as every protocol error.
  try {
    parse_protocol(file);
  } catch (const ProtocolError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": " + message);
  }
}

}  // namespace
}  // namespace knoblab::study
